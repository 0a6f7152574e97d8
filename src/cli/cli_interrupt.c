/* Ctrl-C during `illum render` and `illum bake` (cli.h).  The first one
 * asks the running work to stop early: a render after its current pass, a
 * radiosity or hr solve at its next step, photon tracing or a Linespace
 * injection after its current round, and the result so far is written.
 * Work that cannot stop part-way (a photon kd-tree build, one pass of a
 * huge image) runs on, so the first Ctrl-C also says that a second one quits
 * at once: SA_RESETHAND gives it SIGINT's default action, which ends the
 * process before any output is written (outputs are written after the
 * handler is released, each to a temporary name first). */
#include <signal.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"

volatile sig_atomic_t cli_interrupted = 0;
static volatile sig_atomic_t quiet_notice = 0;

static void on_sigint(int sig)
{
    (void)sig;
    cli_interrupted = 1;
    static const char notice[] =
        "\nillum: stopping early (Ctrl-C again quits at once, writing nothing)\n";
    if (!quiet_notice) /* write(2): async-signal-safe, unlike stdio */
        (void)!write(STDERR_FILENO, notice, sizeof notice - 1);
}

void cli_interrupt_catch(bool quiet, struct sigaction *old)
{
    struct sigaction sa;
    memset(&sa, 0, sizeof sa);
    sa.sa_handler = on_sigint;
    sa.sa_flags = SA_RESETHAND;
    sigemptyset(&sa.sa_mask);
    quiet_notice = quiet;
    sigaction(SIGINT, &sa, old);
}

void cli_interrupt_release(const struct sigaction *old) { sigaction(SIGINT, old, NULL); }
