/* `mpirun -np N illum render --method radiosity|hr|photon|sppm|ibl|linespace|rsm`:
 * the methods other than the path tracer split across MPI ranks through the
 * library's il_distrib (docs/distributed.md).
 * Built only with -DIL_MPI=ON; called by cli_mpi_render. */
#ifndef IL_CLI_MPI_METHODS_H
#define IL_CLI_MPI_METHODS_H

#include <stdbool.h>
#include "illum/illum.h"

/* Every rank calls it with the same options after MPI is up; only rank 0's
 * film (the summed films) and stats are the result, only rank 0 prints
 * (verbose: a line of figures: time, exchanges, bytes). */
il_status cli_mpi_render_method(const il_scene *scene, il_film *film, const il_render_desc *desc,
                                il_render_stats *stats, bool verbose, il_error *err);

#endif
