/* Photon mapping and SPPM split across processes (il_distrib, illum.h;
 * docs/distributed.md).
 *
 * Photons: process r of N traces the indices [lo_r, hi_r) of the pass's
 * range (il_distrib_range: contiguous, in rank order).  A photon's path
 * depends only on (seed, index) (pm_trace.c) and il_pm_trace returns its
 * photons in index order, so the processes' arrays concatenated in rank
 * order are the single-process arrays byte for byte; every process then
 * builds the same maps.
 *
 * Camera pass: 16x16 tiles as in camera_pass.c, tile t on process t mod N,
 * each with all its samples at once.  The tile callback adds a pixel's
 * samples in increasing index, as the passes of il_camera_pass_tiles do one
 * after the other, so every pixel's sums are the same doubles; pixels of
 * other processes stay zero, and x + 0 = x makes the summed films exact. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/photon/pm.h"

#define IL_PM_DISTRIB_TILE 16u

il_status il_pm_trace_split(const il_scene *scene, const il_pm_trace_desc *desc,
                            const il_distrib *d, il_pm_photons *out, il_error *err)
{
    if (!il_distrib_on(d))
        return il_pm_trace(scene, desc, out, err);
    uint64_t lo, hi;
    il_distrib_range(desc->count, d->rank, d->size, &lo, &hi);
    il_pm_trace_desc mine = *desc;
    mine.first = desc->first + lo;
    mine.count = hi - lo;
    il_pm_photons local = {0};
    il_status st = il_pm_trace(scene, &mine, &local, err);
    if (st != IL_OK)
        return st;

    /* One exchange: per process {global count, caustic count} then the
     * global photons, then the caustic ones. */
    size_t bytes = 2 * sizeof(uint64_t) + (local.num_global + local.num_caustic) * sizeof(il_photon);
    unsigned char *send = il_malloc(bytes, err);
    size_t *counts = il_calloc((size_t)d->size, sizeof *counts, err);
    void *all = NULL;
    if (send && counts) {
        uint64_t n[2] = {local.num_global, local.num_caustic};
        memcpy(send, n, sizeof n);
        if (local.num_global)
            memcpy(send + sizeof n, local.global, local.num_global * sizeof(il_photon));
        if (local.num_caustic)
            memcpy(send + sizeof n + local.num_global * sizeof(il_photon), local.caustic,
                   local.num_caustic * sizeof(il_photon));
        st = il_distrib_allgather(d, send, bytes, &all, counts, err);
    } else {
        st = IL_ERR_MEMORY;
    }
    free(send);
    free(local.global);
    free(local.caustic);
    if (st != IL_OK) {
        free(counts);
        return st;
    }

    /* Sizes first, then the two arrays in rank order. */
    uint64_t ng = 0, nc = 0;
    size_t off = 0;
    for (int r = 0; r < d->size; r++) {
        uint64_t n[2];
        if (counts[r] >= sizeof n)
            memcpy(n, (unsigned char *)all + off, sizeof n);
        if (counts[r] < sizeof n || counts[r] != sizeof n + (n[0] + n[1]) * sizeof(il_photon)) {
            st = il_fail(err, IL_ERR_RUNTIME,
                         "photon tracing: process %d sent a malformed photon block", r);
            break;
        }
        ng += n[0];
        nc += n[1];
        off += counts[r];
    }
    il_photon *g = NULL, *c = NULL;
    if (st == IL_OK && ng && !(g = il_malloc(ng * sizeof *g, err)))
        st = IL_ERR_MEMORY;
    if (st == IL_OK && nc && !(c = il_malloc(nc * sizeof *c, err)))
        st = IL_ERR_MEMORY;
    if (st == IL_OK) {
        size_t gi = 0, ci = 0;
        off = 0;
        for (int r = 0; r < d->size; r++) {
            const unsigned char *p = (const unsigned char *)all + off;
            uint64_t n[2];
            memcpy(n, p, sizeof n);
            if (n[0])
                memcpy(g + gi, p + sizeof n, n[0] * sizeof(il_photon));
            if (n[1])
                memcpy(c + ci, p + sizeof n + n[0] * sizeof(il_photon), n[1] * sizeof(il_photon));
            gi += n[0];
            ci += n[1];
            off += counts[r];
        }
        out->global = g;
        out->num_global = ng;
        out->caustic = c;
        out->num_caustic = nc;
        out->rays = local.rays; /* this process's */
    } else {
        free(g);
        free(c);
    }
    free(all);
    free(counts);
    return st;
}

il_status il_pm_camera_pass_split(const il_scene *scene, il_film *film, const il_render_desc *desc,
                                  il_camera_tile_fn tile_fn, const void *method,
                                  il_camera_pass_result *out, il_error *err)
{
    const il_distrib *d = desc->distrib;
    il_camera_pass_ctx ctx = il_camera_pass_ctx_make(scene, film, desc);
    uint32_t spp = desc->spp ? desc->spp : 16u;
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    uint32_t tiles_x = (ctx.width + IL_PM_DISTRIB_TILE - 1) / IL_PM_DISTRIB_TILE;
    uint32_t tiles = tiles_x * ((ctx.height + IL_PM_DISTRIB_TILE - 1) / IL_PM_DISTRIB_TILE);
    uint32_t rank = (uint32_t)d->rank, size = (uint32_t)d->size;
    uint32_t mine = tiles > rank ? (tiles - rank + size - 1) / size : 0; /* t = rank + k size */

    il_film_clear(film);
    double t0 = omp_get_wtime();
    uint64_t rays = 0, bad = 0;
#pragma omp parallel for schedule(dynamic) num_threads(threads) reduction(+ : rays, bad)
    for (uint32_t k = 0; k < mine; k++) {
        uint32_t t = rank + k * size;
        uint32_t x0 = (t % tiles_x) * IL_PM_DISTRIB_TILE, y0 = (t / tiles_x) * IL_PM_DISTRIB_TILE;
        il_camera_tile tile = {
            .x0 = x0,
            .y0 = y0,
            .x1 = x0 + IL_PM_DISTRIB_TILE < ctx.width ? x0 + IL_PM_DISTRIB_TILE : ctx.width,
            .y1 = y0 + IL_PM_DISTRIB_TILE < ctx.height ? y0 + IL_PM_DISTRIB_TILE : ctx.height,
            .first = 0,
            .count = spp,
        };
        tile_fn(method, &ctx, &tile);
        rays += tile.rays;
        bad += tile.nonfinite;
    }
    out->spp = spp;
    out->rays = rays;
    out->nonfinite_samples = bad;
    out->seconds = omp_get_wtime() - t0;
    (void)err;
    return IL_OK;
}
