/* See mpi_session.h and cli_mpi.h: MPI's start and end for one process, the
 * agreement before a render, and rank 0's message when mpirun ends the job. */
#include "cli/mpi/mpi_session.h"

#include <mpi.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#include "cli/cli.h"
#include "cli/cli_mpi.h"

static bool active = false, agreed = false;
static int rank = 0, size = 1;
static int saved_argc = 0;
static char **saved_argv = NULL;
/* Rank 0: the checkpoint of this run, removed once the outputs are written. */
static char ckpt_path[4096];
/* Rank 0: what to say when mpirun ends the job (on_sigterm). */
static char killed_message[4096 + 512];
static volatile size_t killed_length = 0;
static struct sigaction old_sigterm;

void cli_mpi_init(int *argc, char ***argv)
{
    /* Only under a launcher: a plain run must never need MPI. */
    if (!getenv("OMPI_COMM_WORLD_SIZE") && !getenv("PMI_SIZE") && !getenv("PMIX_RANK") &&
        !getenv("MPI_LOCALNRANKS"))
        return;
    int provided;
    if (MPI_Init_thread(argc, argv, MPI_THREAD_FUNNELED, &provided) != MPI_SUCCESS) {
        cli_error("MPI_Init failed; rendering as a single process");
        return;
    }
    active = true;
    saved_argc = *argc;
    saved_argv = *argv;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
}

bool cli_mpi_active(void) { return active; }
int cli_mpi_rank(void) { return rank; }
int cli_mpi_size(void) { return size; }

void cli_mpi_args(int *argc, char ***argv)
{
    *argc = saved_argc;
    *argv = saved_argv;
}

void cli_mpi_agree(int value, int *max_value, int *who)
{
    int in[2] = {value, rank}, out[2];
    MPI_Allreduce(in, out, 1, MPI_2INT, MPI_MAXLOC, MPI_COMM_WORLD);
    agreed = true;
    *max_value = out[0];
    *who = out[1];
}

void cli_mpi_remove_on_success(const char *path)
{
    snprintf(ckpt_path, sizeof ckpt_path, "%s", path);
}

int cli_mpi_finalize(int rc)
{
    if (!active)
        return rc;
    if (!agreed && size > 1) {
        int v, who;
        cli_mpi_agree(CLI_MPI_NOT_RENDERING + rc, &v, &who);
    }
    if (rank == 0 && rc == IL_EXIT_OK && ckpt_path[0])
        unlink(ckpt_path);
    MPI_Finalize();
    return rc;
}

/* A message prepared beforehand: only write() here. */
static void on_sigterm(int sig)
{
    (void)sig;
    if (killed_length > 0) {
        ssize_t n = write(STDERR_FILENO, killed_message, killed_length);
        (void)n;
    }
    _exit(IL_EXIT_RUNTIME);
}

void cli_mpi_kill_notice(const char *ckpt, int done, int tiles)
{
    int n;
    killed_length = 0;
    if (ckpt)
        n = snprintf(killed_message, sizeof killed_message,
                     "illum: distributed render: rank 0 was ended by mpirun (a rank died or the "
                     "job was cancelled); no image is written; checkpoint %s holds %d of %d "
                     "tiles: run the same command again to continue\n",
                     ckpt, done, tiles);
    else
        n = snprintf(killed_message, sizeof killed_message,
                     "illum: distributed render: rank 0 was ended by mpirun (a rank died or the "
                     "job was cancelled); no image is written (with --checkpoint-every S a run "
                     "started again continues where it stopped)\n");
    killed_length = n > 0 && (size_t)n < sizeof killed_message ? (size_t)n : 0;
}

void cli_mpi_kill_notice_begin(const char *ckpt, int done, int tiles)
{
    cli_mpi_kill_notice(ckpt, done, tiles);
    struct sigaction sa = {0};
    sa.sa_handler = on_sigterm;
    sigaction(SIGTERM, &sa, &old_sigterm);
}

void cli_mpi_kill_notice_end(void) { sigaction(SIGTERM, &old_sigterm, NULL); }
