#define _XOPEN_SOURCE 700 /* realpath */
#include "cli/cli.h"

#include "core/atomic_file.h"
#include "core/error.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

void cli_error(const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    fputs("illum: ", stderr);
    vfprintf(stderr, fmt, ap);
    fputc('\n', stderr);
    va_end(ap);
}

bool cli_parse_count(const char *opt, const char *s, uint64_t *out)
{
    uint64_t n = 0;
    if (!cli_parse_u64(opt, s, &n))
        return false;
    if (n < 1 || n > 10000000000ull) {
        cli_error("%s: %s is out of range (1 to 10^10)", opt, s);
        return false;
    }
    *out = n;
    return true;
}

bool cli_parse_u32(const char *opt, const char *s, uint32_t min, uint32_t max, uint32_t *out)
{
    char *end = NULL;
    errno = 0;
    long long v = strtoll(s, &end, 10);
    if (errno || end == s || *end != '\0' || v < (long long)min || v > (long long)max) {
        cli_error("%s: expected a whole number from %u to %u, got '%s'", opt, min, max, s);
        return false;
    }
    *out = (uint32_t)v;
    return true;
}

bool cli_parse_u64(const char *opt, const char *s, uint64_t *out)
{
    char *end = NULL;
    errno = 0;
    if (s[0] == '-') {
        cli_error("%s: expected a non-negative whole number, got '%s'", opt, s);
        return false;
    }
    unsigned long long v = strtoull(s, &end, 10);
    if (errno || end == s || *end != '\0') {
        cli_error("%s: expected a non-negative whole number, got '%s'", opt, s);
        return false;
    }
    *out = (uint64_t)v;
    return true;
}

bool cli_parse_double(const char *opt, const char *s, double min, double max, double *out)
{
    char *end = NULL;
    errno = 0;
    double v = strtod(s, &end);
    if (errno || end == s || *end != '\0' || !isfinite(v) || v < min || v > max) {
        cli_error("%s: expected a number from %g to %g, got '%s'", opt, min, max, s);
        return false;
    }
    *out = v;
    return true;
}

bool cli_parse_on_off(const char *opt, const char *s, bool *out)
{
    if (!strcmp(s, "on") || !strcmp(s, "off")) {
        *out = !strcmp(s, "on");
        return true;
    }
    cli_error("%s: '%s' is neither on nor off", opt, s);
    return false;
}

bool cli_parse_numbers(const char *opt, const char *s, int n, const char *form, double *out)
{
    const char *p = s;
    for (int k = 0; k < n; k++) {
        char *end = NULL;
        errno = 0;
        out[k] = strtod(p, &end);
        if (errno || end == p || !isfinite(out[k]) || *end != (k < n - 1 ? ',' : '\0')) {
            cli_error("%s: expected %s, got '%s'", opt, form, s);
            return false;
        }
        p = end + 1;
    }
    return true;
}

bool cli_parse_vec3(const char *opt, const char *s, il_vec3 *out)
{
    double v[3];
    if (!cli_parse_numbers(opt, s, 3, "three numbers X,Y,Z", v))
        return false;
    *out = (il_vec3){(float)v[0], (float)v[1], (float)v[2]};
    return true;
}

bool cli_parse_sampler(const char *opt, const char *s, il_sampler_type *out)
{
    if (!strcmp(s, "sobol") || !strcmp(s, "pcg")) {
        *out = !strcmp(s, "pcg") ? IL_SAMPLER_PCG : IL_SAMPLER_SOBOL;
        return true;
    }
    cli_error("%s: expected sobol or pcg, got '%s'", opt, s);
    return false;
}

const char *cli_value(int argc, char **argv, int *i)
{
    if (*i + 1 >= argc) {
        cli_error("%s needs a value (see --help)", argv[*i]);
        return NULL;
    }
    (*i)++;
    return argv[*i];
}

void cli_log(il_log_level level, const char *message, void *user)
{
    bool quiet = user && *(const bool *)user;
    if (level == IL_LOG_WARNING && !quiet)
        fprintf(stderr, "illum: warning: %s\n", message);
}

double cli_now_seconds(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int cli_exit_for(il_status st)
{
    switch (st) {
    case IL_OK: return IL_EXIT_OK;
    case IL_ERR_IO:
    case IL_ERR_FORMAT:
    case IL_ERR_INVALID: return IL_EXIT_BAD_INPUT;
    case IL_ERR_MEMORY:
    case IL_ERR_RUNTIME: return IL_EXIT_RUNTIME;
    }
    return IL_EXIT_RUNTIME;
}

bool cli_write_text_atomic(const char *path, const char *text)
{
    il_error err = {0};
    il_atomic_file af;
    il_status st = il_atomic_open(&af, path, &err);
    if (st == IL_OK)
        st = il_atomic_close(&af, fputs(text, af.f) >= 0 ? IL_OK
                                  : il_fail(&err, IL_ERR_IO, "%s: cannot write", path), &err);
    if (st != IL_OK)
        cli_error("%s", err.message);
    return st == IL_OK;
}

void cli_folder_of(const char *path, char *dir, size_t size)
{
    const char *slash = strrchr(path, '/');
    if (!slash)
        snprintf(dir, size, ".");
    else if (slash == path)
        snprintf(dir, size, "/");
    else
        snprintf(dir, size, "%.*s", (int)(slash - path), path);
}

/* The path with its folder resolved (realpath), for comparing outputs:
 * "a.png" and "./a.png" are one file.  The folder exists once
 * il_atomic_check has passed.  False when it cannot be resolved. */
static bool resolved(const char *path, char *out, size_t size)
{
    const char *slash = strrchr(path, '/');
    char dir[PATH_MAX];
    cli_folder_of(path, dir, sizeof dir);
    char real[PATH_MAX];
    if (!realpath(dir, real))
        return false;
    return snprintf(out, size, "%s/%s", real, slash ? slash + 1 : path) < (int)size;
}

int cli_check_outputs(const char *const *paths, int n)
{
    for (int i = 0; i < n; i++) {
        il_error err = {0};
        if (paths[i] && il_atomic_check(paths[i], &err) != IL_OK) {
            cli_error("%s", err.message);
            return cli_exit_for(err.status);
        }
    }
    /* Two outputs in one file: the later would replace the earlier. */
    for (int i = 0; i < n; i++)
        for (int j = i + 1; j < n && paths[i]; j++) {
            char a[2 * PATH_MAX], b[2 * PATH_MAX];
            if (paths[j] && (!strcmp(paths[i], paths[j]) ||
                             (resolved(paths[i], a, sizeof a) && resolved(paths[j], b, sizeof b) &&
                              !strcmp(a, b)))) {
                cli_error("%s and %s name the same file: give each output its own", paths[i], paths[j]);
                return IL_EXIT_BAD_INPUT;
            }
        }
    return IL_EXIT_OK;
}

int cli_load_scene(const char *path, bool quiet, il_scene **out)
{
    return cli_load_scene_env(path, quiet, NULL, out);
}

int cli_load_scene_env(const char *path, bool quiet, const cli_env_options *env, il_scene **out)
{
    static bool quiet_flag;
    quiet_flag = quiet;
    il_error err = {0};
    il_load_desc ld = {.log = cli_log, .log_user = &quiet_flag};
    il_status st = il_scene_load(path, &ld, out, &err);
    if (st == IL_OK && env && (env->file || env->sky || env->sky_only)) {
        /* The map replaces the scene's sky before the light tables are built. */
        int rc = cli_env_apply(*out, env, quiet);
        if (rc != IL_EXIT_OK) {
            il_scene_release(*out);
            *out = NULL;
            return rc;
        }
    }
    if (st == IL_OK)
        st = il_scene_commit(*out, &err);
    if (st != IL_OK) {
        cli_error("%s", err.message);
        il_scene_release(*out);
        *out = NULL;
        return cli_exit_for(st);
    }
    return IL_EXIT_OK;
}

int cli_scene_argument(const char *cmd, const char *arg, const char **scene)
{
    if (arg[0] == '-' && arg[1] != '\0') {
        cli_error("%s: unknown option '%s' (see 'illum %s --help')", cmd, arg, cmd);
        return IL_EXIT_USAGE;
    }
    if (*scene) {
        cli_error("%s: one scene at a time ('%s' is extra)", cmd, arg);
        return IL_EXIT_USAGE;
    }
    *scene = arg;
    return IL_EXIT_OK;
}

int cli_require_scene(const char *cmd, const char *scene)
{
    if (scene)
        return IL_EXIT_OK;
    cli_error("%s: no scene given (see 'illum %s --help')", cmd, cmd);
    return IL_EXIT_USAGE;
}
