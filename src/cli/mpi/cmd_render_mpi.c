/* `mpirun -np N illum render ...`: one path-traced render split across MPI
 * ranks (docs/distributed.md).  MPI start and end, the agreement before the
 * render and the message when mpirun ends the job: mpi_session.c.
 *
 * Work units are runs of the camera pass's 16x16 tiles along a tile row
 * (up to 2 tiles per thread of the rank that asks, so that all its threads
 * have work), each with all its samples (il_render_region).  Rank 0 hands
 * them out on request (dynamic load balancing: a fast rank asks more often)
 * and renders units itself between answering requests; every worker keeps
 * two requests in flight so that it has its next unit while rank 0 is busy
 * with its own.  A worker sends every finished unit's film sums to rank 0,
 * which adds them into its film (zero there before: x + 0 = x exactly), so
 * rank 0's film is at every moment the single-process il_render film on the
 * finished tiles, bit for bit, whatever the rank count and the assignment.
 * That film is what --write-every writes and what a checkpoint saves
 * (mpi_checkpoint.h): a per-tile "done" bitmap and the film; a run started
 * again with the same command skips the done tiles, and since every tile's
 * sums do not depend on when or where it was rendered, the image is the
 * uninterrupted run's, bit for bit.
 *
 * --time: units of TIME_ROUND_SPP samples, the tiles over and over in rounds
 * with a seed per round, until the deadline (the first round always ends).
 *
 * Failures: a rank that fails before the render (bad scene on that node)
 * tells the others through the entry collective (cli_mpi_agree); a unit that
 * fails on a worker is reported to rank 0 with its message; rank 0 then
 * hands out no more work, saves the checkpoint, prints the message and
 * writes no image.  A rank that dies makes mpirun end the job: rank 0 says
 * so on SIGTERM (cli_mpi_kill_notice) and the image writers write atomically
 * (temporary name, rename), so no output is ever a part; the last
 * checkpoint, written the same way, survives for the restart. */
#include "cli/cli_mpi.h"

#include <mpi.h>
#include <omp.h>
#include <signal.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "cli/mpi/mpi_checkpoint.h"
#include "cli/mpi/mpi_methods.h"
#include "cli/mpi/mpi_session.h"
#include "core/error.h"

#define TILE 16
#define TAG_REQ 1    /* worker -> 0: int[REQ_INTS] {kind, value, the worker's threads, unit} */
#define TAG_TEXT 2   /* worker -> 0: an error message after MSG_ERR */
#define TAG_WORK 3   /* 0 -> worker: int[UNIT_INTS] unit; x0 = -1: no more work */
#define TAG_PIXELS 4 /* worker -> 0: after MSG_TILE, the unit's film sums (4 doubles a pixel) */
#define UNIT_INTS 6  /* x0 y0 x1 y1 round spp */
#define REQ_INTS (3 + UNIT_INTS)
#define MSG_READY 0
#define MSG_TILE 1 /* value: the tiles just finished; the unit and its pixels follow */
#define MSG_ERR 2  /* value: its il_status; a TAG_TEXT message follows */
#define DEPTH 2    /* requests a worker keeps in flight */
#define TIME_ROUND_SPP 4u  /* --time: samples per pixel of one round */

typedef struct tally {
    uint64_t rays, nonfinite;
    int tiles;
    double pixel_bytes; /* sent to rank 0 (workers) */
} tally;

/* For the tests (tests/cli/mpi/): IL_MPI_TEST_FAIL=1 fails every unit the
 * rank gets; IL_TEST_MPI_FAIL_RANK=r with IL_TEST_MPI_FAIL_AFTER=k makes
 * rank r fail once it has rendered k units, with an error
 * (IL_TEST_MPI_FAIL_MODE=error, the default) or by dying (=crash), as a
 * node whose render breaks or that goes down would. */
static il_status injected_failure(const int u[UNIT_INTS], int units_done, il_error *err)
{
    const char *fail = getenv("IL_MPI_TEST_FAIL");
    if (fail && !strcmp(fail, "1"))
        return il_fail(err, IL_ERR_RUNTIME, "tile (%d, %d): failure injected by IL_MPI_TEST_FAIL",
                       u[0], u[1]);
    const char *who = getenv("IL_TEST_MPI_FAIL_RANK");
    if (!who || atoi(who) != cli_mpi_rank())
        return IL_OK;
    const char *after = getenv("IL_TEST_MPI_FAIL_AFTER");
    if (units_done < (after ? atoi(after) : 0))
        return IL_OK;
    const char *mode = getenv("IL_TEST_MPI_FAIL_MODE");
    if (mode && !strcmp(mode, "crash"))
        raise(SIGKILL);
    return il_fail(err, IL_ERR_RUNTIME,
                   "tile (%d, %d): failure injected by IL_TEST_MPI_FAIL_RANK after %d units", u[0],
                   u[1], units_done);
}

static il_status render_unit(const il_scene *scene, il_film *film, const il_render_desc *desc,
                             const int u[UNIT_INTS], tally *tl, il_error *err)
{
    static int units_done = 0;
    il_status st = injected_failure(u, units_done, err);
    if (st != IL_OK)
        return st;
    il_render_rect r = {(uint32_t)u[0], (uint32_t)u[1], (uint32_t)u[2], (uint32_t)u[3]};
    il_render_desc d = *desc;
    if (desc->time_limit > 0.0) {
        /* A round of --time: its own samples (a seed per round; round 0
         * keeps the given seed). */
        d.time_limit = 0.0;
        d.spp = (uint32_t)u[5];
        d.seed = desc->seed + (uint64_t)u[4] * 0x9e3779b97f4a7c15ull;
    }
    il_render_stats s;
    st = il_render_region(scene, film, &d, &r, &s, err);
    if (st == IL_OK) {
        units_done++;
        tl->rays += s.rays;
        tl->nonfinite += s.nonfinite_samples;
        tl->tiles += (int)(((r.x1 - r.x0 + TILE - 1) / TILE) * ((r.y1 - r.y0 + TILE - 1) / TILE));
    }
    return st;
}

/* Copies the unit's pixels out of the film (or, add = true, adds them in). */
static void unit_pixels(il_film *film, const int u[UNIT_INTS], double *pixels, bool add)
{
    double *data = il_film_data(film);
    size_t w = il_film_width(film), row = (size_t)(u[2] - u[0]) * 4;
    for (int y = u[1]; y < u[3]; y++) {
        double *f = data + ((size_t)y * w + (size_t)u[0]) * 4, *p = pixels + (size_t)(y - u[1]) * row;
        if (add)
            for (size_t i = 0; i < row; i++)
                f[i] += p[i];
        else
            memcpy(p, f, row * sizeof *p);
    }
}

static void clear_unit(il_film *film, const int u[UNIT_INTS])
{
    double *data = il_film_data(film);
    size_t w = il_film_width(film);
    for (int y = u[1]; y < u[3]; y++)
        memset(data + ((size_t)y * w + (size_t)u[0]) * 4, 0,
               (size_t)(u[2] - u[0]) * 4 * sizeof(double));
}

static int unit_values(const int u[UNIT_INTS]) { return (u[2] - u[0]) * (u[3] - u[1]) * 4; }

static void worker(const il_scene *scene, il_film *film, const il_render_desc *desc, tally *tl)
{
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    int msg[REQ_INTS] = {MSG_READY, 0, threads}, outstanding = 0;
    for (int i = 0; i < DEPTH; i++, outstanding++)
        MPI_Send(msg, REQ_INTS, MPI_INT, 0, TAG_REQ, MPI_COMM_WORLD);
    /* The last unit's pixels go out while the next one renders. */
    double *pixels = malloc((size_t)il_film_width(film) * TILE * 4 * sizeof *pixels);
    MPI_Request sending = MPI_REQUEST_NULL;
    bool failed = false;
    while (outstanding > 0) {
        int u[UNIT_INTS];
        MPI_Recv(u, UNIT_INTS, MPI_INT, 0, TAG_WORK, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
        outstanding--;
        if (u[0] < 0 || failed)
            continue;
        il_error err = {0};
        int before = tl->tiles;
        clear_unit(film, u);
        il_status st = pixels ? render_unit(scene, film, desc, u, tl, &err)
                              : il_fail(&err, IL_ERR_MEMORY, "out of memory for a unit's pixels");
        if (st != IL_OK) {
            /* No answer comes to this one: drain the other request and stop. */
            msg[0] = MSG_ERR;
            msg[1] = (int)st;
            MPI_Send(msg, REQ_INTS, MPI_INT, 0, TAG_REQ, MPI_COMM_WORLD);
            MPI_Send(err.message, (int)strlen(err.message) + 1, MPI_CHAR, 0, TAG_TEXT,
                     MPI_COMM_WORLD);
            failed = true;
            continue;
        }
        MPI_Wait(&sending, MPI_STATUS_IGNORE);
        unit_pixels(film, u, pixels, false);
        msg[0] = MSG_TILE;
        msg[1] = tl->tiles - before;
        memcpy(msg + 3, u, sizeof u);
        MPI_Send(msg, REQ_INTS, MPI_INT, 0, TAG_REQ, MPI_COMM_WORLD);
        MPI_Isend(pixels, unit_values(u), MPI_DOUBLE, 0, TAG_PIXELS, MPI_COMM_WORLD, &sending);
        tl->pixel_bytes += (double)unit_values(u) * sizeof(double);
        outstanding++;
    }
    MPI_Wait(&sending, MPI_STATUS_IGNORE);
    free(pixels);
}

typedef struct dispatcher {
    int next, tiles, tiles_x, workers_left;
    uint32_t width, height, spp;
    int round, rounds;           /* --time: the round handed out, the most rounds */
    double t0, time_limit;       /* MPI_Wtime at the start; --time (0: none) */
    unsigned char *handed;       /* per tile: handed out (this round) */
    unsigned char *done;         /* per tile: all its samples are in the film (not --time) */
    uint32_t *tile_spp;          /* per tile: samples in the film */
    int tiles_done;
    int *stops;                  /* per rank: "no more work" answers sent */
    int *answers;                /* per rank: answers sent */
    double *pixels;              /* a unit's pixels from a worker */
    il_status status;            /* the first failure */
    bool stopped;                /* the progress callback said stop (Ctrl-C) */
    char message[sizeof(((il_error *)0)->message) + 64];
    /* checkpoints (path NULL: none) */
    const char *ckpt;
    double ckpt_every, next_ckpt;
    uint64_t fingerprint;
    bool ckpt_warned;
    int ckpt_writes;
    double ckpt_seconds;         /* writing them (rank 0 renders nothing meanwhile) */
} dispatcher;

static bool deadline_passed(const dispatcher *d)
{
    return d->time_limit > 0.0 && MPI_Wtime() - d->t0 >= d->time_limit;
}

/* The next unit for a rank with `threads` threads: up to 2 tiles per thread
 * along the current tile row, none that is done; false when none is left
 * (or the run stops: a failure, Ctrl-C, --time's deadline after round 0). */
static bool next_unit(dispatcher *d, int threads, int u[UNIT_INTS])
{
    if (d->status != IL_OK || d->stopped || (d->round > 0 && deadline_passed(d)))
        return false;
    for (;;) {
        while (d->next < d->tiles && d->handed[d->next])
            d->next++;
        if (d->next < d->tiles)
            break;
        if (d->round + 1 >= d->rounds || deadline_passed(d))
            return false;
        d->round++; /* --time: the tiles again, with the next round's samples */
        memset(d->handed, 0, (size_t)d->tiles);
        d->next = 0;
    }
    int row = d->next / d->tiles_x, col = d->next % d->tiles_x;
    int n = 0, most = 2 * (threads > 0 ? threads : 1);
    while (n < most && col + n < d->tiles_x && !d->handed[d->next + n]) {
        d->handed[d->next + n] = 1;
        n++;
    }
    u[0] = col * TILE;
    u[1] = row * TILE;
    u[2] = (col + n) * TILE < (int)d->width ? (col + n) * TILE : (int)d->width;
    u[3] = (row + 1) * TILE < (int)d->height ? (row + 1) * TILE : (int)d->height;
    u[4] = d->round;
    uint32_t left = d->spp - (uint32_t)d->round * TIME_ROUND_SPP;
    u[5] = d->time_limit > 0.0 ? (int)(left < TIME_ROUND_SPP ? left : TIME_ROUND_SPP) : (int)d->spp;
    return true;
}

static void save_checkpoint(dispatcher *d, il_film *film)
{
    cli_checkpoint ck = {.fingerprint = d->fingerprint, .width = d->width, .height = d->height,
                         .tiles = (uint32_t)d->tiles, .done = d->done, .film = il_film_data(film)};
    il_error e = {0};
    double t = MPI_Wtime();
    il_status st = cli_checkpoint_write(d->ckpt, &ck, &e);
    d->ckpt_seconds += MPI_Wtime() - t;
    d->ckpt_writes++;
    if (st == IL_OK) {
        cli_mpi_kill_notice(d->ckpt, d->tiles_done, d->tiles);
    } else if (!d->ckpt_warned) { /* the render itself goes on */
        cli_error("warning: %s", e.message);
        d->ckpt_warned = true;
    }
    d->next_ckpt = MPI_Wtime() + d->ckpt_every;
}

/* A unit's pixels are in rank 0's film: count them, checkpoint, report. */
static void unit_finished(dispatcher *d, il_film *film, const il_render_desc *desc,
                          const int u[UNIT_INTS], uint64_t rays)
{
    for (int y = u[1]; y < u[3]; y += TILE)
        for (int x = u[0]; x < u[2]; x += TILE) {
            int t = (y / TILE) * d->tiles_x + x / TILE;
            d->tile_spp[t] += (uint32_t)u[5];
            if (d->time_limit == 0.0 && !d->done[t]) {
                d->done[t] = 1;
                d->tiles_done++;
            }
        }
    if (d->ckpt && MPI_Wtime() >= d->next_ckpt)
        save_checkpoint(d, film);
    if (desc->progress) { /* the progress bar and --write-every */
        /* passes_done: the samples of the tiles done, spread over the film
         * (--time: of the rounds before the one handed out) */
        il_render_progress p = {
            .passes_done = d->time_limit > 0.0
                               ? (uint32_t)d->round * TIME_ROUND_SPP
                               : (uint32_t)((uint64_t)d->spp * (uint64_t)d->tiles_done / (uint64_t)d->tiles),
            .passes_total = d->time_limit > 0.0 ? 0 : d->spp,
            .seconds = MPI_Wtime() - d->t0,
            .time_limit = d->time_limit,
            .rays = rays,
            .film = film};
        if (!desc->progress(&p, desc->progress_user))
            d->stopped = true;
    }
}

/* Answers one request (blocking until one comes). */
static void serve(dispatcher *d, il_film *film, const il_render_desc *desc, const tally *tl)
{
    int msg[REQ_INTS];
    MPI_Status s;
    MPI_Recv(msg, REQ_INTS, MPI_INT, MPI_ANY_SOURCE, TAG_REQ, MPI_COMM_WORLD, &s);
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
    if (msg[0] == MSG_TILE) {
        const int *done = msg + 3;
        MPI_Recv(d->pixels, unit_values(done), MPI_DOUBLE, w, TAG_PIXELS, MPI_COMM_WORLD,
                 MPI_STATUS_IGNORE);
        unit_pixels(film, done, d->pixels, true);
        unit_finished(d, film, desc, done, tl->rays);
    }
    int u[UNIT_INTS] = {-1, -1, -1, -1, 0, 0};
    bool work = next_unit(d, msg[2], u);
    MPI_Send(u, UNIT_INTS, MPI_INT, w, TAG_WORK, MPI_COMM_WORLD);
    d->answers[w]++;
    if (!work && ++d->stops[w] == DEPTH)
        d->workers_left--;
}

/* Rank 0 before the render: the checkpoint to continue from, if any. */
static il_status resume(dispatcher *d, il_film *film, bool verbose, il_error *err)
{
    cli_checkpoint ck = {.fingerprint = d->fingerprint, .width = d->width, .height = d->height,
                         .tiles = (uint32_t)d->tiles, .done = d->done, .film = il_film_data(film)};
    bool found;
    il_status st = cli_checkpoint_read(d->ckpt, &ck, &found, err);
    if (st != IL_OK || !found)
        return st;
    for (int t = 0; t < d->tiles; t++)
        if (d->done[t]) {
            d->handed[t] = 1;
            d->tile_spp[t] = d->spp;
            d->tiles_done++;
        } else { /* rendered from zero, whatever the file holds there */
            int x = (t % d->tiles_x) * TILE, y = (t / d->tiles_x) * TILE;
            int tile[UNIT_INTS] = {x, y, x + TILE < (int)d->width ? x + TILE : (int)d->width,
                                   y + TILE < (int)d->height ? y + TILE : (int)d->height};
            clear_unit(film, tile);
        }
    if (verbose)
        fprintf(stderr, "illum: mpi: resuming from checkpoint %s: %d of %d tiles already rendered\n",
                d->ckpt, d->tiles_done, d->tiles);
    return IL_OK;
}

static il_status leader(const il_scene *scene, il_film *film, const il_render_desc *desc,
                        dispatcher *d, tally *tl, il_error *err)
{
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    /* Every worker's first DEPTH requests are answered before rank 0 renders
     * anything: all ranks start with work however late a worker was
     * scheduled (and the tests' injected failures happen for certain). */
    for (int w = 1; w < cli_mpi_size(); w++)
        while (d->answers[w] < DEPTH && d->workers_left > 0)
            serve(d, film, desc, tl);
    for (;;) {
        int pending = 1;
        while (d->workers_left > 0 && pending) {
            MPI_Iprobe(MPI_ANY_SOURCE, TAG_REQ, MPI_COMM_WORLD, &pending, MPI_STATUS_IGNORE);
            if (pending)
                serve(d, film, desc, tl);
        }
        int u[UNIT_INTS];
        if (next_unit(d, threads, u)) {
            il_error e = {0};
            il_status st = render_unit(scene, film, desc, u, tl, &e);
            if (st == IL_OK)
                unit_finished(d, film, desc, u, tl->rays);
            else
                clear_unit(film, u); /* no part of a unit in the checkpoint */
            if (st != IL_OK && d->status == IL_OK) {
                d->status = st;
                snprintf(d->message, sizeof d->message, "rank 0: %s", e.message);
            }
            continue;
        }
        if (d->workers_left == 0)
            break;
        serve(d, film, desc, tl);
    }
    /* Last, what this run did (also after a failure: the restart needs it). */
    if (d->ckpt)
        save_checkpoint(d, film);
    if (d->status != IL_OK) {
        if (d->ckpt && !d->ckpt_warned)
            return il_fail(err, d->status,
                           "distributed render failed on %s; no image is written; checkpoint %s "
                           "holds %d of %d tiles: run the same command again to continue",
                           d->message, d->ckpt, d->tiles_done, d->tiles);
        return il_fail(err, d->status, "distributed render failed on %s; no image is written",
                       d->message);
    }
    return IL_OK;
}

/* Options that fail on every rank alike (no communication needed). */
static il_status check_job(const il_render_desc *desc, const cli_mpi_job *job, il_error *err)
{
    bool ckpt = job->checkpoint_every > 0.0 || job->checkpoint;
    if (desc->method != IL_METHOD_PT) {
        if (ckpt)
            return il_fail(err, IL_ERR_INVALID,
                           "checkpoints (--checkpoint-every) cover --method pt under mpirun; "
                           "the other methods start again from the beginning after a failure");
        if (job->write_every > 0.0)
            return il_fail(err, IL_ERR_INVALID,
                           "--write-every under mpirun: --method pt only (split, the other "
                           "methods have no image before their end)");
        return IL_OK;
    }
    if (ckpt && desc->time_limit > 0.0)
        return il_fail(err, IL_ERR_INVALID,
                       "checkpoints need a sample count: use --spp, not --time, with "
                       "--checkpoint-every");
    if (job->checkpoint && !(job->checkpoint_every > 0.0))
        return il_fail(err, IL_ERR_INVALID, "--checkpoint needs --checkpoint-every S");
    return IL_OK;
}

il_status cli_mpi_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                         const cli_mpi_job *job, il_render_stats *stats, bool verbose,
                         il_error *err)
{
    memset(stats, 0, sizeof *stats);
    int rank = cli_mpi_rank(), size = cli_mpi_size();
    if (size > 1) {
        int v, who;
        cli_mpi_agree(0, &v, &who);
        /* The same exit status as the failed rank's where it was bad input,
         * so that mpirun's status does not depend on which exits first. */
        if (v >= CLI_MPI_NOT_RENDERING)
            return il_fail(err, v - CLI_MPI_NOT_RENDERING == IL_EXIT_BAD_INPUT ? IL_ERR_INVALID : IL_ERR_RUNTIME,
                           "rank %d failed before the render began (exit status %d; its message "
                           "is above); nothing is written",
                           who, v - CLI_MPI_NOT_RENDERING);
    }
    /* The same options on every rank: these fail everywhere or nowhere. */
    il_status st = check_job(desc, job, err);
    if (st != IL_OK)
        return st;
    if (desc->method != IL_METHOD_PT) /* photon, sppm, radiosity: mpi_methods.c */
        return cli_mpi_render_method(scene, film, desc, stats, verbose, err);

    double t0 = MPI_Wtime();
    il_film_clear(film);
    uint32_t w = il_film_width(film), h = il_film_height(film);
    int tiles = (int)(((w + TILE - 1) / TILE) * ((h + TILE - 1) / TILE));
    uint32_t spp = desc->spp ? desc->spp : desc->time_limit > 0.0 ? UINT32_MAX : 16u;
    tally tl = {0};
    dispatcher d = {.tiles = tiles,
                    .tiles_x = (int)((w + TILE - 1) / TILE),
                    .width = w,
                    .height = h,
                    .spp = spp,
                    .rounds = desc->time_limit > 0.0 ? (int)((spp - 1) / TIME_ROUND_SPP + 1) : 1,
                    .t0 = t0,
                    .time_limit = desc->time_limit,
                    .workers_left = size - 1,
                    .status = IL_OK};
    if (rank == 0) {
        d.handed = calloc((size_t)tiles, 1);
        d.done = calloc((size_t)tiles, 1);
        d.tile_spp = calloc((size_t)tiles, sizeof *d.tile_spp);
        d.stops = calloc((size_t)size, sizeof *d.stops);
        d.answers = calloc((size_t)size, sizeof *d.answers);
        d.pixels = malloc((size_t)w * TILE * 4 * sizeof *d.pixels);
        if (!d.handed || !d.done || !d.tile_spp || !d.stops || !d.answers || !d.pixels)
            st = il_fail(err, IL_ERR_MEMORY, "distributed render: out of memory on rank 0");
        if (st == IL_OK && job->checkpoint_every > 0.0) {
            static char ckpt_path[4096];
            if (job->checkpoint)
                snprintf(ckpt_path, sizeof ckpt_path, "%s", job->checkpoint);
            else
                snprintf(ckpt_path, sizeof ckpt_path, "%s.ckpt", job->output);
            d.ckpt = ckpt_path;
            d.ckpt_every = job->checkpoint_every;
            d.next_ckpt = t0 + job->checkpoint_every;
            int argc;
            char **argv;
            cli_mpi_args(&argc, &argv);
            d.fingerprint = cli_checkpoint_fingerprint(argc, argv, desc, w, h);
            st = resume(&d, film, verbose, err);
            if (st == IL_OK) /* not ours to remove when it does not fit */
                cli_mpi_remove_on_success(ckpt_path);
        }
    }
    /* Rank 0's setup (a checkpoint that does not fit) ends every rank. */
    int status = (int)st;
    MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
    /* Rank 0 until the end of the render's collectives (a rank that dies
     * leaves it waiting in one): mpirun's SIGTERM gets a message. */
    if (rank == 0)
        cli_mpi_kill_notice_begin(d.ckpt && d.tiles_done > 0 ? d.ckpt : NULL, d.tiles_done, d.tiles);
    if (status == IL_OK) {
        if (rank == 0)
            st = leader(scene, film, desc, &d, &tl, err);
        else
            worker(scene, film, desc, &tl);
        status = (int)st;
        /* Every rank ends with rank 0's status (and so the same exit status). */
        MPI_Bcast(&status, 1, MPI_INT, 0, MPI_COMM_WORLD);
    }
    double t_render = MPI_Wtime() - t0;
    free(d.handed);
    free(d.done);
    free(d.stops);
    free(d.answers);
    free(d.pixels);
    uint32_t least = spp;
    for (int t = 0; rank == 0 && t < tiles; t++)
        least = d.tile_spp[t] < least ? d.tile_spp[t] : least;
    free(d.tile_spp);
    if (status != IL_OK) {
        if (rank == 0)
            cli_mpi_kill_notice_end();
        return rank == 0 ? st : il_fail(err, (il_status)status, "the distributed render failed");
    }

    uint64_t mine[2] = {tl.rays, tl.nonfinite}, all[2] = {0, 0};
    MPI_Reduce(mine, all, 2, MPI_UINT64_T, MPI_SUM, 0, MPI_COMM_WORLD);
    double sent = 0.0;
    MPI_Reduce(&tl.pixel_bytes, &sent, 1, MPI_DOUBLE, MPI_SUM, 0, MPI_COMM_WORLD);
    int *per_rank = rank == 0 ? calloc((size_t)size, 2 * sizeof(int)) : NULL;
    int me[2] = {tl.tiles, (int)(t_render * 1000.0)};
    MPI_Gather(me, 2, MPI_INT, per_rank, 2, MPI_INT, 0, MPI_COMM_WORLD);
    if (rank == 0) {
        cli_mpi_kill_notice_end();
        stats->spp = least; /* --time: the fewest samples of any tile */
        stats->rays = all[0];
        stats->nonfinite_samples = all[1];
        stats->seconds = MPI_Wtime() - t0;
        if (verbose && per_rank) {
            fprintf(stderr, "illum: mpi: %d ranks, %d tiles of %dx%d (tiles per rank:", size, tiles,
                    TILE, TILE);
            for (int r = 0; r < size; r++)
                fprintf(stderr, " %d", per_rank[2 * r]);
            fprintf(stderr, "); render %.3f s; pixels sent to rank 0: %.3g MB", t_render,
                    sent / 1e6);
            if (d.ckpt)
                fprintf(stderr, "; %d checkpoints of %.3g MB in %.3g s", d.ckpt_writes,
                        (double)w * h * 32.0 / 1e6, d.ckpt_seconds);
            fputc('\n', stderr);
        }
    }
    free(per_rank);
    return IL_OK;
}
