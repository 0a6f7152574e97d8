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
 * Camera pass: il_camera_pass_tiles's own split (every size-th tile). */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/photon/pm.h"

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
        out->emitted = desc->count; /* desc->watch is for one process alone (pm_render.c) */
    } else {
        free(g);
        free(c);
    }
    free(all);
    free(counts);
    return st;
}
