/* The injection pass (Nilles 2017, sec. 3.2): light paths leave every
 * light, bounce off the surfaces by sampling their BSDFs and survive by
 * Russian roulette (as photons do, Jensen 2001, 5.2), and every segment
 * after the first hit, i.e. light that has scattered at least once, leaves
 * its flux in the Linespaces of the voxels it crosses.
 *
 * The thesis adds the irradiance E = I cos(theta) / d^2 that the segment's
 * start receives and reads E / count back.  That is exact for a point light
 * and one bounce only, and has no form for an area light.  Here a segment
 * carrying flux Phi that enters a voxel through its boundary adds Phi * c
 * to the entry of the shaft and direction its line runs through there, c
 * the line's chord through the voxel (face to face, wherever the segment
 * ends).  The flux entering through dA within dw is L cos dA dw = L dG
 * (the line measure, Santalo), so after P paths
 *
 *   L_shaft = sum(Phi c) / (P M_shaft)      [W m / (m^3 sr) = W m^-2 sr^-1]
 *
 * with M_shaft = int c dG (il_ls_shaft_measures) is an unbiased estimate of
 * the radiance entering the voxel along the shaft's lines, averaged over
 * the (point, direction) pairs of the voxel whose line lies in the shaft:
 * what a point x inside sees along such a line when nothing lies between
 * x and the entry face, which is what the sampling pass's occlusion test
 * checks.  Light leaving a surface inside the voxel is not deposited
 * there: a point that sees that surface is occluded and traces on.  A
 * track length (Phi times the segment's length inside the voxel, Spanier
 * & Gelbard 1969) would estimate the mean over every point of the voxel,
 * inside solids too, where no light runs, and read a block's faces up to
 * 24% dark (docs/linespace.md, "Injection").  For a point light the
 * expected flux a first bounce at x sends into dw is rho/pi E(x) cos dA dw
 * with E = I cos/d^2, the thesis's term; for an area light E(x) = int Le
 * cos cos' / r^2 dA' comes out of the same sampling.
 *
 * In a scene with portals and light from outside (docs/linespace.md,
 * "Windows"), a share of the paths start at the portals as the light
 * coming in by them (methods/portal_light.h, il_portal_light_share),
 * and the lights' own paths end where they enter by one, deposited up to
 * the crossing.
 *
 * Deterministic for a seed: each path's random numbers are keyed by its
 * index, chunks of paths are traced in parallel into their own deposit
 * lists and added in chunk order, whatever the thread count. */
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "core/rng.h"
#include "methods/light_emit.h"
#include "methods/linespace/ls.h"
#include "methods/portal_light.h"
#include "scene/bsdf.h"
#include "trace/trace.h"

#define LS_CHUNK 1024u

/* A deposit: first voxel << 32 | (shaft number * 2 + direction), as the
 * walk finds it, then, once the chunk is traced, the entry 2 * slot +
 * direction (resolve_slots), NO_ENTRY for a shaft not stored. */
typedef struct deposit {
    uint64_t entry;
    float rgb[3];
} deposit;
#define NO_ENTRY UINT64_MAX

typedef struct chunk {
    deposit *d;
    size_t count, cap;
    uint64_t rays;
    bool oom;
} chunk;

static void push(chunk *c, uint64_t entry, il_vec3 v)
{
    if (c->count == c->cap) {
        size_t cap = c->cap ? 2 * c->cap : 4096;
        deposit *p = realloc(c->d, cap * sizeof(deposit));
        if (!p) {
            c->oom = true;
            return;
        }
        c->d = p;
        c->cap = cap;
    }
    c->d[c->count++] = (deposit){entry, {v.x, v.y, v.z}};
}

/* What a segment leaves in one voxel it crosses (il_ls_walk's visit). */
typedef struct deposit_ctx {
    chunk *c;
    il_vec3 power;
} deposit_ctx;

static void deposit_visit(void *user, uint32_t voxel, uint32_t shaft, uint32_t dir, float chord, bool entered)
{
    deposit_ctx *dc = user;
    if (entered)
        push(dc->c, (uint64_t)voxel << 32 | (2u * shaft + dir), v3_scale(dc->power, chord));
}

/* The chunk's deposits' slots, looked up after its paths are traced: the
 * bit words are read a few deposits ahead of their use, so their cache
 * misses overlap instead of stalling the walk one by one.  A shaft that is
 * not stored (no geometry in it) gets NO_ENTRY and is skipped. */
static void resolve_slots(const il_linespace *ls, chunk *c)
{
    enum { AHEAD = 8 };
    for (size_t i = 0; i < c->count; i++) {
        if (i + AHEAD < c->count) { /* the bit word of a later deposit's shaft */
            uint64_t a = c->d[i + AHEAD].entry;
            uint32_t shaft = (uint32_t)a >> 1;
            __builtin_prefetch(&ls->words[(a >> 32) * ls->mask_words + shaft / 64u]);
        }
        deposit *e = &c->d[i];
        uint32_t voxel = (uint32_t)(e->entry >> 32), shaft = (uint32_t)e->entry >> 1,
                 dir = (uint32_t)e->entry & 1u;
        int64_t slot = il_ls_slot(ls, voxel, shaft);
        e->entry = slot >= 0 ? 2u * (uint64_t)slot + dir : NO_ENTRY;
    }
}

static void trace_path(const il_scene *s, const il_linespace *ls, uint32_t depth, uint64_t seed,
                       uint64_t index, float portal_share, chunk *c)
{
    il_pcg32 rng = il_pcg32_seed(il_hash_combine(seed ^ 0x4c53u, index), index);
    float u[IL_LIGHT_EMIT_DIMS];
    for (int i = 0; i < IL_LIGHT_EMIT_DIMS; i++)
        u[i] = il_pcg32_float(&rng);
    il_light_emission e;
    /* Split at the portals, the Linespace holds the light inside alone,
     * which the environment's own paths never reach (they stop where they
     * would enter): il_light_emit_inside draws none. */
    bool emitted = il_light_emit_inside(s, u, portal_share, &rng, depth, &e);
    c->rays += e.rays;
    if (!emitted)
        return;
    const il_tracer *tr = s->tracer;
    il_ray ray = {.org = e.org, .tmin = 0.0f, .dir = e.dir, .tmax = INFINITY};
    il_vec3 power = e.power;
    /* The portals' light from a surface outside has bounced there. */
    for (uint32_t bounces = e.scattered ? 1 : 0, seg = 0;; bounces++, seg++) {
        il_hit hit;
        c->rays++;
        bool found = il_trace_closest(tr, &ray, &hit);
        float t_end = found ? hit.t : INFINITY, t_cross;
        /* A sun's or a street lamp's path that meets the outside before a
         * window lights only the outside: nothing of it is kept. */
        if (seg == 0 && !il_portal_light_starts_inside(s, &e, &ray, t_end))
            return;
        /* Entering by a portal, the path ends there: the portals' light
         * brings what it would bring in.  Leaving by one, it ends too:
         * outside, its light would reach voxels that straddle a wall (an
         * L-shaped room's grid spans the yard in its crook), and what
         * comes back in the portals' light brings. */
        bool stops = il_portal_light_stops(s, &e, seg, &ray, t_end, &t_cross);
        if (stops)
            t_end = t_cross;
        else if (e.split && il_portal_light_leaves(s, &ray, t_end, &t_cross)) {
            stops = true;
            t_end = t_cross;
        }
        /* Segment `bounces` has scattered that many times: the first
         * (straight from the light) is direct light, which the sampling
         * pass takes by shadow rays. */
        if (bounces > 0) {
            /* The start's distance off its surface: at most twice
             * il_offset_origin's offset. */
            float mag = il_maxf(fabsf(ray.org.x), il_maxf(fabsf(ray.org.y), fabsf(ray.org.z)));
            float start_tol = 2.0f * (il_trace_epsilon(tr) + mag * 4.0f * FLT_EPSILON);
            deposit_ctx dc = {c, power};
            il_ls_walk(ls, ray.org, ray.dir, t_end, start_tol, deposit_visit, &dc);
        }
        if (stops || !found || bounces >= depth)
            break;
        il_surface surf;
        il_scene_surface(s, hit.mesh, hit.prim, hit.b1, hit.b2, &surf);
        il_vec3 wo = v3_neg(ray.dir);
        il_bsdf b;
        il_bsdf_init(&b, s, &surf);
        bool delta;
        if (!il_light_path_scatter(tr, &surf, &b, wo, &rng, &power, &ray, &delta))
            break;
    }
}

/* A coarse shaft's sums over the stored shafts it holds (docs/linespace.md,
 * "Coarse level"): radiance = sum(Phi c) / (P sum M), the same estimate
 * as a fine entry's over all their lines together. */
typedef struct coarse_sum {
    double measure;
    double phi[2][3];
    bool filled[2];
} coarse_sum;

/* Adds one stored shaft of measure `meas`: its two entries' sums
 * (acc[3 dir + c]) and deposit counts. */
static void coarse_add(coarse_sum *c, double meas, const double *acc, const uint8_t *filled)
{
    c->measure += meas;
    for (int dir = 0; dir < 2; dir++) {
        for (int k = 0; k < 3; k++)
            c->phi[dir][k] += acc[3 * dir + k];
        c->filled[dir] |= filled[dir] != 0;
    }
}

static void coarse_finish(il_linespace *ls, uint32_t voxel, const coarse_sum *cs, uint64_t paths)
{
    for (uint32_t c = 0; c < ls->num_coarse; c++) {
        double scale = cs[c].measure > 0.0 && paths > 0 ? 1.0 / ((double)paths * cs[c].measure) : 0.0;
        for (uint32_t dir = 0; dir < 2; dir++) {
            il_ls_coarse *e = il_ls_coarse_entry(ls, voxel, c, dir);
            for (int k = 0; k < 3; k++)
                e->rgb[k] = (float)(cs[c].phi[dir][k] * scale);
            e->filled = cs[c].filled[dir];
        }
    }
}

/* Adds the deposits of chunks ch[0..n-1] to the sums, in chunk order and
 * in each chunk's order, so the sums do not depend on the thread count.
 * The threads split the entries, not the deposits: each reads every
 * deposit and adds those of its own range, so every sum still gets its
 * terms in that order; the sums' cache misses are fetched a few deposits
 * ahead. */
static void merge_round(const chunk *ch, size_t n, uint64_t num_entries, int threads, double *acc,
                        uint8_t *filled, uint64_t *deposits)
{
    enum { AHEAD = 8 };
    uint64_t count = 0;
#pragma omp parallel num_threads(threads) reduction(+ : count)
    {
        uint64_t parts = 1, part = 0;
#ifdef _OPENMP
        parts = (uint64_t)omp_get_num_threads();
        part = (uint64_t)omp_get_thread_num();
#endif
        const uint64_t lo = num_entries * part / parts, hi = num_entries * (part + 1u) / parts;
        for (size_t k = 0; k < n; k++) {
            const deposit *d = ch[k].d;
            for (size_t i = 0; i < ch[k].count; i++) {
                if (i + AHEAD < ch[k].count) {
                    uint64_t ahead = d[i + AHEAD].entry;
                    if (ahead >= lo && ahead < hi)
                        __builtin_prefetch(acc + 3u * ahead, 1);
                }
                uint64_t e = d[i].entry; /* NO_ENTRY is in no range */
                if (e < lo || e >= hi)
                    continue;
                count++;
                double *a = acc + 3u * e;
                a[0] += d[i].rgb[0];
                a[1] += d[i].rgb[1];
                a[2] += d[i].rgb[2];
                filled[e] += filled[e] < 255u; /* deposits, saturating */
            }
        }
    }
    *deposits += count;
}

static double seconds_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

il_status il_ls_inject(const il_scene *scene, const il_ls_settings *st, uint64_t seed, int threads,
                       il_linespace *ls, il_ls_inject_result *out, il_error *err)
{
    memset(out, 0, sizeof *out);
    if (threads <= 0) {
#ifdef _OPENMP
        threads = omp_get_max_threads();
#else
        threads = 1;
#endif
    }
    const uint64_t paths = st->inject_rays;
    const uint64_t num_entries = 2u * ls->num_stored;
    double *acc = calloc(3u * num_entries + 1, sizeof(double));
    uint8_t *filled = calloc(num_entries + 1, 1); /* entry 2 slot + dir holds a deposit */
    uint64_t num_chunks = (paths + LS_CHUNK - 1) / LS_CHUNK;
    uint64_t round = (uint64_t)threads * 16u;
    if (round > num_chunks)
        round = num_chunks ? num_chunks : 1;
    chunk *ch = calloc((size_t)round, sizeof(chunk));
    if (!acc || !ch || !filled) {
        free(acc);
        free(filled);
        free(ch);
        return il_fail(err, IL_ERR_MEMORY, "linespace: out of memory for the injection");
    }
    /* The share of the paths that start at the portals (0: none). */
    const float share = ls->portal_light ? il_portal_light_share(scene) : 0.0f;
    bool oom = false;
    uint64_t injected = 0;
    double t0 = seconds_now();
    for (uint64_t c0 = 0; c0 < num_chunks && !oom; c0 += round) {
        /* A stop between rounds keeps whole rounds: the first `injected`
         * paths, as if only those had been asked for. */
        if (st->on_step) {
            il_linespace_progress p = {injected, paths, seconds_now() - t0};
            if (!st->on_step(&p, st->on_step_user)) {
                out->stopped = true;
                break;
            }
        }
        int64_t n = (int64_t)(num_chunks - c0 < round ? num_chunks - c0 : round);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
        for (int64_t k = 0; k < n; k++) {
            chunk c = ch[k];
            c.count = 0;
            c.rays = 0;
            c.oom = false;
            uint64_t lo = (c0 + (uint64_t)k) * LS_CHUNK;
            uint64_t hi = lo + LS_CHUNK < paths ? lo + LS_CHUNK : paths;
            for (uint64_t i = lo; i < hi && !c.oom; i++)
                trace_path(scene, ls, st->inject_depth, seed, i, share, &c);
            resolve_slots(ls, &c);
            ch[k] = c;
        }
        for (int64_t k = 0; k < n; k++) {
            oom |= ch[k].oom;
            out->rays += ch[k].rays;
        }
        merge_round(ch, (size_t)n, num_entries, threads, acc, filled, &out->deposits);
        uint64_t end = (c0 + (uint64_t)n) * LS_CHUNK;
        injected = end < paths ? end : paths;
    }
    out->injected = injected;
    for (uint64_t k = 0; k < round; k++)
        free(ch[k].d);
    free(ch);
    if (oom) {
        free(acc);
        free(filled);
        return il_fail(err, IL_ERR_MEMORY, "linespace: out of memory tracing light paths");
    }
    /* Radiance = sum(Phi c) / (P M).  Without the solid-angle correction
     * every shaft is taken to be the mean size 2 pi V / (15 N^4), as a
     * reading that ignores how much of the sphere a shaft covers does. */
    double volume = (double)ls->vsize.x * ls->vsize.y * ls->vsize.z;
    double mean_measure = 2.0 * IL_PI * volume / (double)ls->num_shafts;
    /* Per coarse shaft of the voxel at hand: its stored shafts' summed
     * measure, then per direction the sums of Phi c and whether any got a
     * deposit. */
    coarse_sum *cs = ls->coarse ? malloc(ls->num_coarse * sizeof(coarse_sum)) : NULL;
    if (ls->coarse && !cs) {
        free(acc);
        free(filled);
        return il_fail(err, IL_ERR_MEMORY, "linespace: out of memory for the coarse level");
    }
    /* With a coarse level, an entry holding fewer deposits than
     * st->coarse_below reads as empty, so the coarse one is read instead. */
    unsigned min_deposits = cs ? st->coarse_below : 1u;
    for (uint32_t v = 0; v < ls->num_voxels; v++) {
        if (cs)
            memset(cs, 0, ls->num_coarse * sizeof(coarse_sum));
        for (uint32_t w = 0; w < ls->mask_words; w++) {
            il_ls_word *word = &ls->words[(size_t)v * ls->mask_words + w];
            uint64_t m = word->mask;
            while (m) {
                uint32_t shaft = w * 64u + (uint32_t)__builtin_ctzll(m);
                m &= m - 1u;
                int64_t slot = il_ls_slot(ls, v, shaft);
                double meas = st->solid_angle ? (double)ls->measure[shaft] : mean_measure;
                double scale = meas > 0.0 && injected > 0 ? 1.0 / ((double)injected * meas) : 0.0;
                il_ls_rec *r = &ls->recs[slot];
                for (uint32_t dir = 0; dir < 2; dir++) {
                    uint64_t e = 2u * (uint64_t)slot + dir;
                    for (int c = 0; c < 3; c++)
                        r->rgb[dir][c] = (float)(acc[3u * e + c] * scale);
                    if (filled[e] >= min_deposits) {
                        r->info |= IL_LS_REC_FILLED(dir);
                        word->filled[dir] |= 1ull << (shaft % 64u);
                    }
                }
                if (cs)
                    coarse_add(&cs[ls->coarse_of[shaft]], meas, acc + 6u * (uint64_t)slot,
                               filled + 2u * (uint64_t)slot);
            }
        }
        if (cs)
            coarse_finish(ls, v, cs, injected);
    }
    free(cs);
    free(acc);
    free(filled);
    return IL_OK;
}
