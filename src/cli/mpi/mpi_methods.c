/* Every method but the path tracer under mpirun (docs/distributed.md):
 * the library splits the work itself (il_distrib, illum.h: photon ranges,
 * form-factor rows, hierarchical radiosity's links, and every method's
 * camera-pass tiles, IBL's, RSM's and Linespace's included) and needs one
 * collective, an allgather of bytes, which this file implements with MPI;
 * here too the films are summed on rank 0 and the counters of every rank
 * added.  Every exchange is timed in two parts: a barrier (waiting for the
 * slowest rank: load imbalance) and the allgather (the transfer), and its
 * bytes counted, for the figures line and the scaling model. */
#include "cli/mpi/mpi_methods.h"

#include <limits.h>
#include <mpi.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "core/error.h"

typedef struct exchange_tally {
    MPI_Win tiles;     /* rank 0's tile counter for il_distrib.claim */
    uint64_t claims;   /* this rank's claims */
    uint64_t calls;
    uint64_t bytes;    /* bytes gathered: what every rank holds after the exchanges */
    uint64_t sent;     /* this rank's own part of them */
    double wait;       /* seconds in the barrier before each exchange */
    double transfer;   /* seconds in the allgathers */
} exchange_tally;

/* A rank that cannot take part in an exchange would leave the others
 * waiting in it: the job ends. */
static void abort_job(int rank, const char *what)
{
    cli_error("distributed render: rank %d: %s; ending the job, nothing is written", rank, what);
    MPI_Abort(MPI_COMM_WORLD, IL_EXIT_RUNTIME);
}

static int mpi_allgather(void *user, const void *data, size_t bytes, void **out, size_t *counts)
{
    exchange_tally *t = user;
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    double t0 = MPI_Wtime();
    MPI_Barrier(MPI_COMM_WORLD);
    double t1 = MPI_Wtime();
    unsigned long long mine = bytes, *all = malloc((size_t)size * sizeof *all);
    if (!all)
        abort_job(rank, "out of memory");
    MPI_Allgather(&mine, 1, MPI_UNSIGNED_LONG_LONG, all, 1, MPI_UNSIGNED_LONG_LONG, MPI_COMM_WORLD);
    size_t total = 0;
    for (int r = 0; r < size; r++) {
        counts[r] = (size_t)all[r];
        total += (size_t)all[r];
    }
    *out = NULL;
    if (total > 0) {
        unsigned char *buf = malloc(total);
        int *cnt = malloc((size_t)size * sizeof *cnt), *disp = malloc((size_t)size * sizeof *disp);
        if (!buf || !cnt || !disp)
            abort_job(rank, "out of memory for an exchange");
        if (total <= (size_t)INT_MAX) {
            size_t off = 0;
            for (int r = 0; r < size; r++) {
                cnt[r] = (int)counts[r];
                disp[r] = (int)off;
                off += counts[r];
            }
            MPI_Allgatherv(data, (int)bytes, MPI_BYTE, buf, cnt, disp, MPI_BYTE, MPI_COMM_WORLD);
        } else {
            /* MPI counts are int: each rank broadcasts its part in chunks. */
            const size_t chunk = (size_t)1 << 30;
            size_t off = 0;
            for (int r = 0; r < size; r++) {
                if (r == rank && bytes)
                    memcpy(buf + off, data, bytes);
                for (size_t o = 0; o < counts[r]; o += chunk) {
                    size_t n = counts[r] - o < chunk ? counts[r] - o : chunk;
                    MPI_Bcast(buf + off + o, (int)n, MPI_BYTE, r, MPI_COMM_WORLD);
                }
                off += counts[r];
            }
        }
        free(cnt);
        free(disp);
        *out = buf;
    }
    free(all);
    double t2 = MPI_Wtime();
    t->calls++;
    t->bytes += total;
    t->sent += bytes;
    t->wait += t1 - t0;
    t->transfer += t2 - t1;
    return 0;
}

/* il_distrib.claim: an atomic fetch-and-add on rank 0's counter (MPI
 * one-sided, passive target: rank 0 does not have to answer; across nodes
 * the MPI library may progress it only when rank 0 enters MPI, at its own
 * next claim). */
static uint64_t mpi_claim(void *user, uint64_t count)
{
    exchange_tally *t = user;
    uint64_t prev = 0;
    MPI_Win_lock(MPI_LOCK_SHARED, 0, 0, t->tiles);
    MPI_Fetch_and_op(&count, &prev, MPI_UINT64_T, 0, 0, MPI_SUM, t->tiles);
    MPI_Win_unlock(0, t->tiles);
    t->claims++;
    return prev;
}

/* Sums the films on rank 0 (each pixel has one non-zero contributor: the
 * sum is exact). */
static void reduce_film(il_film *film, int rank)
{
    size_t n = (size_t)il_film_width(film) * il_film_height(film) * 4;
    double *data = il_film_data(film);
    const size_t chunk = (size_t)1 << 26; /* MPI counts are int */
    for (size_t off = 0; off < n; off += chunk) {
        int cnt = (int)(n - off < chunk ? n - off : chunk);
        if (rank == 0)
            MPI_Reduce(MPI_IN_PLACE, data + off, cnt, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
        else
            MPI_Reduce(data + off, NULL, cnt, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    }
}

static void print_figures(const il_render_desc *desc, const il_render_stats *stats, int size,
                          const double *per_rank, const exchange_tally *t, double film_mb,
                          double t_reduce)
{
    /* per_rank: {render s, wait s, transfer s, tile claims} per rank */
    double wait_max = 0.0, xfer_max = 0.0;
    fprintf(stderr, "illum: mpi: %d ranks, %s: render s per rank:", size, cli_method_name(desc->method));
    for (int r = 0; r < size; r++) {
        fprintf(stderr, " %.3f", per_rank[4 * r]);
        wait_max = per_rank[4 * r + 1] > wait_max ? per_rank[4 * r + 1] : wait_max;
        xfer_max = per_rank[4 * r + 2] > xfer_max ? per_rank[4 * r + 2] : xfer_max;
    }
    fprintf(stderr, "; camera tile claims per rank:");
    for (int r = 0; r < size; r++)
        fprintf(stderr, " %.0f", per_rank[4 * r + 3]);
    unsigned passes = desc->method == IL_METHOD_SPPM ? stats->spp
                      : desc->method == IL_METHOD_PHOTON ? 1u
                                                         : (unsigned)t->calls;
    if (passes == 0)
        passes = 1;
    fprintf(stderr,
            "; %llu exchanges, %.4g MB gathered (%.4g MB sent by rank 0), transfer %.3g s, "
            "waiting %.3g s (most of any rank); per %s: %.4g MB, transfer %.3g s; film reduce "
            "%.3g MB per rank in %.3g s\n",
            (unsigned long long)t->calls, (double)t->bytes / 1e6, (double)t->sent / 1e6, xfer_max,
            wait_max, desc->method == IL_METHOD_RADIOSITY ? "row block" : "pass",
            (double)t->bytes / 1e6 / passes, xfer_max / passes, film_mb, t_reduce);
}

il_status cli_mpi_render_method(const il_scene *scene, il_film *film, const il_render_desc *desc,
                                il_render_stats *stats, bool verbose, il_error *err)
{
    int rank, size;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
    /* Progress and the solve's step callback would let one rank stop
     * alone; the library does not call them when split. */
    exchange_tally tally = {0};
    uint64_t *counter = NULL;
    MPI_Win_allocate(rank == 0 ? (MPI_Aint)sizeof(uint64_t) : 0, (int)sizeof(uint64_t), MPI_INFO_NULL,
                     MPI_COMM_WORLD, &counter, &tally.tiles);
    if (rank == 0) {
        MPI_Win_lock(MPI_LOCK_EXCLUSIVE, 0, 0, tally.tiles);
        *counter = 0;
        MPI_Win_unlock(0, tally.tiles);
    }
    MPI_Barrier(MPI_COMM_WORLD);
    il_distrib dist = {.rank = rank, .size = size, .allgather = mpi_allgather, .user = &tally,
                       .claim = mpi_claim};
    il_render_desc d = *desc;
    d.progress = NULL;
    d.progress_user = NULL;
    d.distrib = &dist;

    double t0 = MPI_Wtime();
    il_status st = il_render(scene, film, &d, stats, err);
    double t_render = MPI_Wtime() - t0;
    /* Bad options fail on every rank before any exchange; anything else
     * (out of memory) fails on one rank while the others wait in an
     * exchange, so the job has to end here. */
    if (st != IL_OK && st != IL_ERR_INVALID)
        abort_job(rank, err->message);
    int in[2] = {(int)st, rank}, out[2];
    MPI_Allreduce(in, out, 1, MPI_2INT, MPI_MAXLOC, MPI_COMM_WORLD);
    MPI_Win_free(&tally.tiles);
    if (out[0] != IL_OK)
    {
        if (st != IL_OK)
            return st;
        return il_fail(err, (il_status)out[0], "rank %d failed (its message is above)", out[1]);
    }

    double t1 = MPI_Wtime();
    reduce_film(film, rank);
    uint64_t mine[4] = {stats->rays, stats->nonfinite_samples, stats->photon.photon_rays,
                        stats->radiosity.rows_computed};
    uint64_t sum[4] = {0, 0, 0, 0};
    MPI_Reduce(mine, sum, 4, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    double t_reduce = MPI_Wtime() - t1;
    double me[4] = {t_render, tally.wait, tally.transfer, (double)tally.claims};
    double *per_rank = rank == 0 ? malloc((size_t)size * sizeof me) : NULL;
    MPI_Gather(me, 4, MPI_DOUBLE, per_rank, 4, MPI_DOUBLE, 0, MPI_COMM_WORLD);
    if (rank == 0) {
        stats->rays = sum[0];
        stats->nonfinite_samples = sum[1];
        stats->photon.photon_rays = sum[2];
        stats->radiosity.rows_computed = sum[3];
        stats->seconds = MPI_Wtime() - t0;
        if (verbose && per_rank)
            print_figures(desc, stats, size, per_rank, &tally,
                          (double)il_film_width(film) * il_film_height(film) * 32.0 / 1e6, t_reduce);
    }
    free(per_rank);
    return IL_OK;
}
