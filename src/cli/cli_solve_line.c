/* The progress line of a radiosity or hr solve (cli.h): one line on stderr,
 * redrawn in place when stderr is a terminal, and the Ctrl-C flag the
 * solve's callback reads to stop early. */
#include <stdarg.h>
#include <stdio.h>
#include <unistd.h>

#include "cli/cli.h"

/* Seconds between two drawings (a solve may report thousands of times a second). */
#define REDRAW_INTERVAL 0.1

void cli_solve_line_start(cli_solve_line *l, bool quiet, const volatile sig_atomic_t *stop)
{
    l->draw = !quiet && isatty(STDERR_FILENO);
    l->drawn = false;
    l->last_draw = 0.0;
    l->stop = stop;
}

bool cli_solve_line_update(cli_solve_line *l, double seconds, bool now, const char *fmt, ...)
{
    if (l->draw && (now || !l->drawn || seconds - l->last_draw >= REDRAW_INTERVAL)) {
        char text[160];
        va_list ap;
        va_start(ap, fmt);
        vsnprintf(text, sizeof text, fmt, ap);
        va_end(ap);
        /* Padded: a shorter line must cover the longer one it replaces. */
        fprintf(stderr, "\r%-72s", text);
        fflush(stderr);
        l->last_draw = seconds;
        l->drawn = true;
    }
    return !(l->stop && *l->stop);
}

void cli_solve_line_end(cli_solve_line *l)
{
    if (l->drawn)
        fputc('\n', stderr);
    l->drawn = false;
}
