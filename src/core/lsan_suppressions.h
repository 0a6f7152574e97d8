/* For builds with -DIL_SANITIZE=ON: assimp 5.2 leaks its importer's buffers
 * when it rejects a corrupt file (the error path of every loader test and of
 * `illum render broken.obj`).  That memory is not illum's, so LeakSanitizer,
 * which calls these functions, is told to skip it.  Include this header in
 * exactly one file of a program: it defines them. */
#ifndef IL_CORE_LSAN_SUPPRESSIONS_H
#define IL_CORE_LSAN_SUPPRESSIONS_H

#ifdef __SANITIZE_ADDRESS__
const char *__lsan_default_suppressions(void);
const char *__lsan_default_suppressions(void)
{
    return "leak:libassimp.so\n";
}

/* ... and not to list the suppressed leaks at exit either. */
const char *__lsan_default_options(void);
const char *__lsan_default_options(void)
{
    return "print_suppressions=0";
}
#endif

#endif
