/* `mpirun -np N illum render ...`: one path-traced render split across MPI
 * ranks (docs/distributed.md).  The only file of illum that sees mpi.h.
 *
 * Work units are runs of the camera pass's 16x16 tiles along a tile row
 * (up to 2 tiles per thread of the rank that asks, so that all its threads
 * have work), each with all its samples (il_render_region).  Rank 0 hands
 * them out on request (dynamic load balancing: a fast rank asks more often)
 * and renders units itself between answering requests; every worker keeps
 * two requests in flight so that it has its next unit while rank 0 is busy
 * with its own.  At the end the films
 * (zero outside each rank's tiles) are summed on rank 0.  Every pixel has
 * exactly one non-zero contributor, and x + 0 = x exactly in IEEE
 * arithmetic, so the reduced film is bit-identical to the single-process
 * il_render film whatever the rank count and the tile assignment.
 *
 * Failures: a rank that fails before the render (bad scene on that node)
 * tells the others through the entry collective (see agree()); a tile that
 * fails on a worker is reported to rank 0 with its message; rank 0 then
 * hands out no more work, prints the message and writes nothing.  A rank
 * that dies makes mpirun end the job before rank 0 writes anything, and the
 * image writers write atomically (temporary name, rename). */
#include "cli/cli_mpi.h"

#include <mpi.h>
#include <omp.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/mpi/mpi_methods.h"
#include "core/error.h"

#define TILE 16
#define TAG_REQ 1  /* worker -> 0: int[3] {kind, value, the worker's threads} */
#define TAG_TEXT 2 /* worker -> 0: an error message after MSG_ERR */
#define TAG_WORK 3 /* 0 -> worker: int[4] region x0 y0 x1 y1; x0 = -1: no more work */
#define MSG_READY 0
#define MSG_TILE 1 /* value: the tiles just finished */
#define MSG_ERR 2  /* value: its il_status; a TAG_TEXT message follows */
#define DEPTH 2    /* requests a worker keeps in flight */
#define NOT_RENDERING 1000 /* agree(): a rank that will not render (+ its exit status) */

static bool active = false, agreed = false;
static int rank = 0, size = 1;

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
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    MPI_Comm_size(MPI_COMM_WORLD, &size);
}

bool cli_mpi_active(void) { return active; }
int cli_mpi_rank(void) { return rank; }
int cli_mpi_size(void) { return size; }

/* The collective every rank takes part in once: at the start of the render
 * (value 0) or, for a rank that never got there, at exit (NOT_RENDERING +
 * its exit status).  Returns the largest value and the rank that gave it. */
static void agree(int value, int *max_value, int *who)
{
    int in[2] = {value, rank}, out[2];
    MPI_Allreduce(in, out, 1, MPI_2INT, MPI_MAXLOC, MPI_COMM_WORLD);
    agreed = true;
    *max_value = out[0];
    *who = out[1];
}

int cli_mpi_finalize(int rc)
{
    if (!active)
        return rc;
    if (!agreed && size > 1) {
        int v, who;
        agree(NOT_RENDERING + rc, &v, &who);
    }
    MPI_Finalize();
    return rc;
}

typedef struct tally {
    uint64_t rays, nonfinite;
    int tiles;
} tally;

static il_status render_unit(const il_scene *scene, il_film *film, const il_render_desc *desc,
                             const int u[4], tally *tl, il_error *err)
{
    il_render_rect r = {(uint32_t)u[0], (uint32_t)u[1], (uint32_t)u[2], (uint32_t)u[3]};
    /* For the tests (tests/cli/mpi/): a rank started with IL_MPI_TEST_FAIL=1
     * fails every tile it gets, as a node whose render breaks would. */
    const char *fail = getenv("IL_MPI_TEST_FAIL");
    if (fail && !strcmp(fail, "1"))
        return il_fail(err, IL_ERR_RUNTIME, "tile (%d, %d): failure injected by IL_MPI_TEST_FAIL",
                       u[0], u[1]);
    il_render_stats s;
    il_status st = il_render_region(scene, film, desc, &r, &s, err);
    if (st == IL_OK) {
        tl->rays += s.rays;
        tl->nonfinite += s.nonfinite_samples;
        tl->tiles += (int)(((r.x1 - r.x0 + TILE - 1) / TILE) * ((r.y1 - r.y0 + TILE - 1) / TILE));
    }
    return st;
}

static void worker(const il_scene *scene, il_film *film, const il_render_desc *desc, tally *tl)
{
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    int msg[3] = {MSG_READY, 0, threads}, outstanding = 0;
    for (int i = 0; i < DEPTH; i++, outstanding++)
        MPI_Send(msg, 3, MPI_INT, 0, TAG_REQ, MPI_COMM_WORLD);
    bool failed = false;
    while (outstanding > 0) {
        int u[4];
        MPI_Recv(u, 4, MPI_INT, 0, TAG_WORK, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        outstanding--;
        if (u[0] < 0 || failed)
            continue;
        il_error err = {0};
        int before = tl->tiles;
        il_status st = render_unit(scene, film, desc, u, tl, &err);
        if (st != IL_OK) {
            /* No answer comes to this one: drain the other request and stop. */
            msg[0] = MSG_ERR;
            msg[1] = (int)st;
            MPI_Send(msg, 3, MPI_INT, 0, TAG_REQ, MPI_COMM_WORLD);
            MPI_Send(err.message, (int)strlen(err.message) + 1, MPI_CHAR, 0, TAG_TEXT,
                     MPI_COMM_WORLD);
            failed = true;
            continue;
        }
        msg[0] = MSG_TILE;
        msg[1] = tl->tiles - before;
        MPI_Send(msg, 3, MPI_INT, 0, TAG_REQ, MPI_COMM_WORLD);
        outstanding++;
    }
}

typedef struct dispatcher {
    int next, tiles, tiles_x, workers_left;
    uint32_t width, height;
    int *stops;             /* per rank: "no more work" answers sent */
    il_status status;       /* the first failure */
    char message[sizeof(((il_error *)0)->message) + 64];
} dispatcher;

/* The next unit for a rank with `threads` threads: up to 2 tiles per thread
 * along the current tile row; false when none is left. */
static bool next_unit(dispatcher *d, int threads, int u[4])
{
    if (d->status != IL_OK || d->next >= d->tiles)
        return false;
    int row = d->next / d->tiles_x, col = d->next % d->tiles_x;
    int n = 2 * (threads > 0 ? threads : 1);
    if (n > d->tiles_x - col)
        n = d->tiles_x - col;
    d->next += n;
    u[0] = col * TILE;
    u[1] = row * TILE;
    u[2] = (col + n) * TILE < (int)d->width ? (col + n) * TILE : (int)d->width;
    u[3] = (row + 1) * TILE < (int)d->height ? (row + 1) * TILE : (int)d->height;
    return true;
}

/* Answers one request (blocking until one comes). */
static void serve(dispatcher *d)
{
    int msg[3];
    MPI_Status s;
    MPI_Recv(msg, 3, MPI_INT, MPI_ANY_SOURCE, TAG_REQ, MPI_COMM_WORLD, &s);
    int w = s.MPI_SOURCE;
    if (msg[0] == MSG_ERR) {
        char text[sizeof(((il_error *)0)->message)];
        MPI_Recv(text, (int)sizeof text, MPI_CHAR, w, TAG_TEXT, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        text[sizeof text - 1] = '\0';
        if (d->status == IL_OK) {
            d->status = msg[1] != IL_OK ? (il_status)msg[1] : IL_ERR_RUNTIME;
            snprintf(d->message, sizeof d->message, "rank %d: %s", w, text);
        }
        d->workers_left--;
        return;
    }
    int u[4] = {-1, -1, -1, -1};
    bool work = next_unit(d, msg[2], u);
    MPI_Send(u, 4, MPI_INT, w, TAG_WORK, MPI_COMM_WORLD);
    if (!work && ++d->stops[w] == DEPTH)
        d->workers_left--;
}

static il_status leader(const il_scene *scene, il_film *film, const il_render_desc *desc,
                        int tiles, tally *tl, il_error *err)
{
    dispatcher d = {.tiles = tiles,
                    .tiles_x = (int)((il_film_width(film) + TILE - 1) / TILE),
                    .width = il_film_width(film),
                    .height = il_film_height(film),
                    .workers_left = size - 1,
                    .status = IL_OK};
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    d.stops = calloc((size_t)size, sizeof *d.stops);
    if (!d.stops) { /* the workers wait for answers: end the whole job */
        cli_error("distributed render: out of memory on rank 0");
        MPI_Abort(MPI_COMM_WORLD, IL_EXIT_RUNTIME);
    }
    for (;;) {
        int pending = 1;
        while (d.workers_left > 0 && pending) {
            MPI_Iprobe(MPI_ANY_SOURCE, TAG_REQ, MPI_COMM_WORLD, &pending, MPI_STATUS_IGNORE);
            if (pending)
                serve(&d);
        }
        int u[4];
        if (next_unit(&d, threads, u)) {
            il_error e = {0};
            il_status st = render_unit(scene, film, desc, u, tl, &e);
            if (st != IL_OK && d.status == IL_OK) {
                d.status = st;
                snprintf(d.message, sizeof d.message, "rank 0: %s", e.message);
            }
            continue;
        }
        if (d.workers_left == 0)
            break;
        serve(&d);
    }
    free(d.stops);
    if (d.status != IL_OK)
        return il_fail(err, d.status, "distributed render failed on %s", d.message);
    return IL_OK;
}

il_status cli_mpi_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                         il_render_stats *stats, bool verbose, il_error *err)
{
    memset(stats, 0, sizeof *stats);
    if (size > 1) {
        int v, who;
        agree(0, &v, &who);
        /* The same exit status as the failed rank's where it was bad input,
         * so that mpirun's status does not depend on which exits first. */
        if (v >= NOT_RENDERING)
            return il_fail(err, v - NOT_RENDERING == IL_EXIT_BAD_INPUT ? IL_ERR_INVALID : IL_ERR_RUNTIME,
                           "rank %d failed before the render began (exit status %d; its message "
                           "is above); nothing is written",
                           who, v - NOT_RENDERING);
    }
    /* The same options on every rank: these fail everywhere or nowhere. */
    if (desc->method != IL_METHOD_PT) /* photon, sppm, radiosity: mpi_methods.c */
        return cli_mpi_render_method(scene, film, desc, stats, verbose, err);
    if (desc->time_limit > 0.0)
        return il_fail(err, IL_ERR_INVALID,
                       "distributed rendering (mpirun) renders a sample count: use --spp, not --time");

    double t0 = MPI_Wtime();
    il_film_clear(film);
    uint32_t w = il_film_width(film), h = il_film_height(film);
    int tiles = (int)(((w + TILE - 1) / TILE) * ((h + TILE - 1) / TILE));
    tally tl = {0};
    il_status st = IL_OK;
    if (rank == 0)
        st = leader(scene, film, desc, tiles, &tl, err);
    else
        worker(scene, film, desc, &tl);
    double t_render = MPI_Wtime() - t0;

    /* Every rank ends with rank 0's status (and so the same exit status). */
    int status = (int)st;
    MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
    if (status != IL_OK)
        return rank == 0 ? st : il_fail(err, (il_status)status, "the distributed render failed");

    /* The reduction: see the top of the file for why the sum is exact. */
    double t1 = MPI_Wtime();
    size_t n = (size_t)w * h * 4;
    double *data = il_film_data(film);
    const size_t chunk = 1u << 26; /* MPI counts are int */
    for (size_t off = 0; off < n; off += chunk) {
        int cnt = (int)(n - off < chunk ? n - off : chunk);
        if (rank == 0)
            MPI_Reduce(MPI_IN_PLACE, data + off, cnt, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
        else
            MPI_Reduce(data + off, NULL, cnt, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    }
    uint64_t mine[2] = {tl.rays, tl.nonfinite}, all[2] = {0, 0};
    MPI_Reduce(mine, all, 2, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    double t_reduce = MPI_Wtime() - t1;
    int *per_rank = rank == 0 ? calloc((size_t)size, 2 * sizeof(int)) : NULL;
    int me[2] = {tl.tiles, (int)(t_render * 1000.0)};
    MPI_Gather(me, 2, MPI_INT, per_rank, 2, MPI_INT, 0, MPI_COMM_WORLD);
    if (rank == 0) {
        stats->spp = desc->spp ? desc->spp : 16u;
        stats->rays = all[0];
        stats->nonfinite_samples = all[1];
        stats->seconds = MPI_Wtime() - t0;
        if (verbose && per_rank) {
            fprintf(stderr, "illum: mpi: %d ranks, %d tiles of %dx%d (tiles per rank:", size, tiles,
                    TILE, TILE);
            for (int r = 0; r < size; r++)
                fprintf(stderr, " %d", per_rank[2 * r]);
            fprintf(stderr, "); render %.3f s; film reduce %.3g MB per rank in %.3g s\n", t_render,
                    (double)n * sizeof(double) / 1e6, t_reduce);
        }
    }
    free(per_rank);
    return IL_OK;
}
