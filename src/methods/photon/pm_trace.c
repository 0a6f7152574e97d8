/* Photon tracing (Jensen 2001, chapter 5; pbrt-v3 16.2.2): photons leave
 * the lights (methods/light_emit.c), bounce off the surfaces by sampling their BSDFs,
 * survive by Russian roulette on the sampled reflectance, and leave a copy
 * of themselves at every non-delta surface they reach after their first
 * bounce (direct light is computed with shadow rays instead). */
#include <stdlib.h>
#include <string.h>

#ifdef _OPENMP
#include <omp.h>
#endif

#include "core/error.h"
#include "core/rng.h"
#include "methods/photon/pm.h"
#include "methods/light_emit.h"
#include "methods/portal_light.h"
#include "trace/trace.h"

/* Photons per parallel work item.  Fixed, so the work and the order of the
 * results never depend on the thread count. */
#define IL_PM_CHUNK 4096u

static inline uint64_t trace_one(const il_scene *s, uint64_t seed, uint64_t index, uint32_t max_depth,
                                 bool at_portals, il_pm_deposit_fn deposit, void *user)
{
    /* The photon's own stream: keyed by (seed, index) only. */
    il_pcg32 rng = il_pcg32_seed(il_hash_combine(seed, index), index);
    float u[IL_LIGHT_EMIT_DIMS];
    for (int i = 0; i < IL_LIGHT_EMIT_DIMS; i++)
        u[i] = il_pcg32_float(&rng);
    il_light_emission e;
    if (!il_light_emit(s, u, at_portals ? il_portal_light_share(s) : 0.0f, &rng, max_depth, &e))
        return e.rays;

    const il_tracer *tr = s->tracer;
    il_ray ray = {.org = e.org, .tmin = 0.0f, .dir = e.dir, .tmax = INFINITY};
    il_vec3 power = e.power;
    /* Jensen 2001, 9.1: the caustic map holds L S+ D light, which only
     * mirrors and glass have turned since it left the light; a diffuse (or
     * glossy) bounce gives the photon to the global map for good.  ("The
     * last bounce was specular" also took L D S+ D light, which a final
     * gather reaches through the mirror as well: counted twice.)  The
     * portals' light from a surface outside is a caustic when that surface
     * was a mirror or glass. */
    bool caustic = !e.scattered || e.caustic;
    uint64_t rays = e.rays;
    /* The portals' light from a surface outside has bounced there. */
    for (uint32_t bounces = e.scattered ? 1 : 0, seg = 0;; bounces++, seg++) {
        il_hit hit;
        rays++;
        bool found = il_trace_closest(tr, &ray, &hit);
        if (il_portal_light_stops(s, &e, seg, &ray, found ? hit.t : INFINITY, NULL))
            break;          /* entered by a portal: the portals' light brings it */
        if (!found)
            break;          /* left the scene */
        il_surface surf;
        il_scene_surface(s, hit.mesh, hit.prim, hit.b1, hit.b2, &surf);
        il_vec3 wo = v3_neg(ray.dir);
        il_bsdf b;
        il_bsdf_init(&b, s, &surf);

        if (bounces > 0 && !il_bsdf_is_delta(&b)) {
            il_pm_deposit d;
            d.p = surf.p;
            d.n = v3_dot(surf.ng, wo) >= 0.0f ? surf.ng : v3_neg(surf.ng);
            d.wi = wo;
            d.power = power;
            d.caustic = caustic;
            deposit(user, &d);
        }
        if (bounces >= max_depth)
            break;

        bool delta;
        if (!il_light_path_scatter(tr, &surf, &b, wo, &rng, &power, &ray, &delta))
            break;          /* absorbed */
        caustic = caustic && delta;
    }
    return rays;
}

uint64_t il_pm_trace_photon(const il_scene *scene, uint64_t seed, uint64_t index, uint32_t max_depth,
                            bool at_portals, il_pm_deposit_fn deposit, void *user)
{
    return trace_one(scene, seed, index, max_depth, at_portals, deposit, user);
}

/* ------------------------------------------------------- parallel tracing */

typedef struct photon_buf {
    il_photon *items;
    size_t count, cap;
} photon_buf;

typedef struct chunk_ctx {
    photon_buf global, caustic;
    bool split;
    bool oom;          /* an append failed: the trace fails */
    uint64_t rays;
} chunk_ctx;

static bool buf_reserve(photon_buf *b, size_t need)
{
    if (need <= b->cap)
        return true;
    size_t cap = b->cap ? b->cap : 1024;
    while (cap < need)
        cap *= 2;
    if (cap > SIZE_MAX / sizeof(il_photon))
        return false;
    il_photon *p = realloc(b->items, cap * sizeof(il_photon));
    if (!p)
        return false;
    b->items = p;
    b->cap = cap;
    return true;
}

static void chunk_deposit(void *user, const il_pm_deposit *d)
{
    chunk_ctx *c = user;
    photon_buf *b = c->split && d->caustic ? &c->caustic : &c->global;
    if (c->oom || !buf_reserve(b, b->count + 1)) {
        c->oom = true;
        return;
    }
    b->items[b->count++] = il_photon_pack(d->p, d->power, d->wi, d->n);
}

/* Appends src to dst (growing it geometrically); false when out of memory. */
static bool buf_append(photon_buf *dst, const photon_buf *src)
{
    if (src->count == 0)
        return true;
    if (!buf_reserve(dst, dst->count + src->count))
        return false;
    memcpy(dst->items + dst->count, src->items, src->count * sizeof(il_photon));
    dst->count += src->count;
    return true;
}

/* Gives the array back at its exact size (NULL when empty). */
static il_photon *buf_release(photon_buf *b)
{
    if (b->count == 0) {
        free(b->items);
        return NULL;
    }
    il_photon *p = realloc(b->items, b->count * sizeof(il_photon));
    return p ? p : b->items;
}

il_status il_pm_trace(const il_scene *scene, const il_pm_trace_desc *desc, il_pm_photons *out,
                      il_error *err)
{
    memset(out, 0, sizeof *out);
    if (!scene || !scene->committed || !scene->tracer)
        return il_fail(err, IL_ERR_INVALID, "photon tracing: the scene is not committed");
    if (desc->count == 0)
        return IL_OK;
    if (desc->first > UINT64_MAX - desc->count)
        return il_fail(err, IL_ERR_INVALID, "photon tracing: photon indices overflow");

    int threads = desc->threads;
#ifdef _OPENMP
    if (threads <= 0)
        threads = omp_get_max_threads();
#endif
    if (threads <= 0)
        threads = 1;

    uint64_t num_chunks = (desc->count + IL_PM_CHUNK - 1) / IL_PM_CHUNK;
    /* Chunks are traced a round at a time and appended in order, so only a
     * round's worth of chunk buffers exists beside the output at once. */
    uint64_t round = (uint64_t)threads * 8u;
    if (round < 16)
        round = 16;
    if (round > num_chunks)
        round = num_chunks;
    chunk_ctx *ctx = calloc((size_t)round, sizeof(chunk_ctx));
    if (!ctx)
        return il_fail(err, IL_ERR_MEMORY, "photon tracing: out of memory");

    photon_buf global = {0}, caustic = {0};
    bool oom = false;
    uint64_t rays = 0, emitted = 0;
    for (uint64_t c0 = 0; c0 < num_chunks && !oom; c0 += round) {
        /* A stop between rounds keeps whole rounds: the first `emitted`
         * indices, as if only those had been asked for. */
        if (!il_pm_watch_report(desc->watch, IL_PHOTON_TRACING, emitted, desc->count))
            break;
        int64_t n = (int64_t)(num_chunks - c0 < round ? num_chunks - c0 : round);
#pragma omp parallel for schedule(dynamic, 1) num_threads(threads)
        for (int64_t k = 0; k < n; k++) {
            /* Filled in a local copy: the neighbouring contexts belong to
             * other threads and would share its cache lines. */
            chunk_ctx c = ctx[k];
            c.global.count = c.caustic.count = 0;
            c.split = desc->split;
            c.oom = false;
            c.rays = 0;
            uint64_t lo = (c0 + (uint64_t)k) * IL_PM_CHUNK;
            uint64_t hi = lo + IL_PM_CHUNK < desc->count ? lo + IL_PM_CHUNK : desc->count;
            for (uint64_t i = lo; i < hi && !c.oom; i++)
                c.rays += trace_one(scene, desc->seed, desc->first + i, desc->max_depth,
                                    desc->at_portals, chunk_deposit, &c);
            ctx[k] = c;
        }
        for (int64_t k = 0; k < n && !oom; k++) {
            oom = ctx[k].oom || !buf_append(&global, &ctx[k].global) ||
                  !buf_append(&caustic, &ctx[k].caustic);
            rays += ctx[k].rays;
        }
        uint64_t end = (c0 + (uint64_t)n) * IL_PM_CHUNK;
        emitted = end < desc->count ? end : desc->count;
    }
    for (uint64_t k = 0; k < round; k++) {
        free(ctx[k].global.items);
        free(ctx[k].caustic.items);
    }
    free(ctx);
    if (oom) {
        free(global.items);
        free(caustic.items);
        return il_fail(err, IL_ERR_MEMORY, "photon tracing: out of memory for %llu photons",
                       (unsigned long long)desc->count);
    }
    out->num_global = global.count;
    out->global = buf_release(&global);
    out->num_caustic = caustic.count;
    out->caustic = buf_release(&caustic);
    out->rays = rays;
    out->emitted = emitted;
    return IL_OK;
}
