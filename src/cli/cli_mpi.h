/* Distributed rendering with MPI (docs/distributed.md).  Built only with
 * -DIL_MPI=ON (src/cli/mpi/, the only files that see mpi.h);
 * otherwise these are stubs for a single process. */
#ifndef IL_CLI_MPI_H
#define IL_CLI_MPI_H

#include <stdbool.h>
#include "illum/illum.h"

/* What a distributed render needs from the command line beyond il_render's
 * options (docs/distributed.md, "Failures and checkpoints"). */
typedef struct cli_mpi_job {
    const char *output;        /* the first output: the checkpoint is <output>.ckpt */
    const char *checkpoint;    /* --checkpoint FILE; NULL: <output>.ckpt */
    double checkpoint_every;   /* --checkpoint-every seconds; 0: no checkpoints */
    double write_every;        /* --write-every seconds (written by desc->progress) */
} cli_mpi_job;

#ifdef IL_MPI
/* Starts MPI when the program was launched by mpirun/mpiexec (its
 * environment says so); a plain run stays a single process without MPI. */
void cli_mpi_init(int *argc, char ***argv);
/* Ends MPI with the program's exit status: a failed rank whose run the
 * others cannot finish (it failed before the render began) aborts the job.
 * Status 0 on rank 0 (the outputs are written) removes the checkpoint. */
int cli_mpi_finalize(int rc);
/* True when MPI runs (launched by mpirun, any rank count): renders then go
 * through cli_mpi_render. */
bool cli_mpi_active(void);
int cli_mpi_rank(void);
int cli_mpi_size(void);
/* il_render split across the ranks: rank 0 hands out 16x16 tiles (all
 * samples each), every rank renders with il_render_region and sends each
 * finished unit's pixels to rank 0 (which checkpoints them, see job, and
 * calls desc->progress with the film so far).  Every rank calls it; only
 * rank 0's film and stats are the result and only rank 0 prints (verbose:
 * a line of figures). */
il_status cli_mpi_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                         const cli_mpi_job *job, il_render_stats *stats, bool verbose,
                         il_error *err);
#else
static inline void cli_mpi_init(int *argc, char ***argv) { (void)argc; (void)argv; }
static inline int cli_mpi_finalize(int rc) { return rc; }
static inline bool cli_mpi_active(void) { return false; }
static inline int cli_mpi_rank(void) { return 0; }
static inline int cli_mpi_size(void) { return 1; }
static inline il_status cli_mpi_render(const il_scene *scene, il_film *film,
                                       const il_render_desc *desc, const cli_mpi_job *job,
                                       il_render_stats *stats, bool verbose, il_error *err)
{
    (void)verbose;
    (void)job;
    return il_render(scene, film, desc, stats, err);
}
#endif

#endif
