/* Shared pieces of the `illum` program: exit codes, option parsing, logging. */
#ifndef IL_CLI_CLI_H
#define IL_CLI_CLI_H

#include <stdbool.h>
#include <stdint.h>
#include "illum/illum.h"

/* Exit status of every sub-command (docs/cli.md). */
enum {
    IL_EXIT_OK = 0,
    IL_EXIT_BAD_INPUT = 1,   /* scene, file or option value */
    IL_EXIT_USAGE = 2,       /* unknown command or option, missing argument */
    IL_EXIT_RUNTIME = 3,     /* the render or a dependency failed */
    IL_EXIT_DIFFERENT = 4,   /* compare: images differ more than --max-rmse/--max-rel-mse */
    IL_EXIT_INTERRUPTED = 130
};

/* Prints "illum: <message>" to stderr. */
void cli_error(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

/* Parsers of option values; on failure they print which option and why and return false. */
bool cli_parse_u32(const char *opt, const char *s, uint32_t min, uint32_t max, uint32_t *out);
bool cli_parse_u64(const char *opt, const char *s, uint64_t *out);
bool cli_parse_double(const char *opt, const char *s, double min, double max, double *out);
bool cli_parse_vec3(const char *opt, const char *s, il_vec3 *out);

/* Argument cursor: fetches the value after option argv[*i], or reports a usage error. */
const char *cli_value(int argc, char **argv, int *i);

/* The log callback that prints loader warnings ("illum: warning: ...") unless quiet. */
void cli_log(il_log_level level, const char *message, void *user);

/* Exit status for an il_status. */
int cli_exit_for(il_status st);

/* Writes text to path through a temporary file and a rename. */
bool cli_write_text_atomic(const char *path, const char *text);

/* Loads SCENE (file or built-in name) and commits it, printing errors. */
int cli_load_scene(const char *path, bool quiet, il_scene **out);

int cmd_render(int argc, char **argv);
int cmd_info(int argc, char **argv);
int cmd_compare(int argc, char **argv);

#endif
