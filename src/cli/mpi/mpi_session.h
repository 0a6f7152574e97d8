/* The MPI session of one `illum` process under mpirun (mpi_session.c):
 * what the distributed renders (cmd_render_mpi.c, mpi_methods.c) share
 * beyond cli_mpi.h. */
#ifndef IL_CLI_MPI_SESSION_H
#define IL_CLI_MPI_SESSION_H

/* cli_mpi_agree's value for a rank that will not render: this + its exit
 * status. */
#define CLI_MPI_NOT_RENDERING 1000

/* The collective every rank takes part in once: at the start of the render
 * (value 0) or, for a rank that never got there, at exit (CLI_MPI_NOT_RENDERING
 * + its exit status).  Returns the largest value and the rank that gave it. */
void cli_mpi_agree(int value, int *max_value, int *who);

/* The command line as MPI_Init left it (the checkpoint's fingerprint). */
void cli_mpi_args(int *argc, char ***argv);

/* Rank 0: a checkpoint that cli_mpi_finalize removes when the program ends
 * with status 0 (the outputs are written: nothing to continue). */
void cli_mpi_remove_on_success(const char *path);

/* Rank 0, around a render's collectives: mpirun ends every rank of a job one
 * of whose ranks died (SIGTERM, then SIGKILL), and rank 0 then says what that
 * means for the outputs and the checkpoint (ckpt NULL: none yet; done of
 * tiles in it).  _begin installs the handler, cli_mpi_kill_notice updates
 * the message after a checkpoint, _end restores the old handler. */
void cli_mpi_kill_notice_begin(const char *ckpt, int done, int tiles);
void cli_mpi_kill_notice(const char *ckpt, int done, int tiles);
void cli_mpi_kill_notice_end(void);

#endif
