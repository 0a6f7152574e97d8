/* Shading a tile with a run of lights.
 *
 * Shadow rays of one directional light from the points of a tile are
 * parallel and start close together: they are cast together, one stream
 * per light and tile (il_trace_visibility_n), so they walk the same nodes of
 * the BVH one after another.  Rays that cannot carry light are never cast:
 * lights below the surface's geometric or shading horizon, black lights,
 * zero BSDF values.
 *
 * Determinism and progressiveness: every pixel belongs to one tile, a tile
 * is shaded by one thread, and each pixel's sum takes the lights in index
 * order and, per light, its camera samples in index order.  So the sum is
 * the same whatever the thread count, and the same whether lights 0..M-1
 * came in one batch or in several. */
#include "methods/ibl/ibl_shade.h"

#include <string.h>

#include "scene/lights.h"

/* The tile's vertices: from the cache, or traced (and, on the first pass,
 * their base term added to the pixels and the cache filled). */
static const il_ibl_vertex *tile_vertices(const il_ibl_job *job, uint32_t t, bool first,
                                          il_ibl_scratch *sc, uint32_t *count, il_ibl_tile_stats *ts)
{
    il_ibl_vertex *slot = job->cache ? job->cache + (size_t)t * job->tile_samples : sc->vertices;
    if (job->cache && !first) {
        *count = job->cache_count[t];
        return slot;
    }
    const il_ibl_camera *c = &job->cam;
    uint32_t T = job->tile, w = c->ctx.width, h = c->ctx.height;
    uint32_t x0 = (t % job->tiles_x) * T, y0 = (t / job->tiles_x) * T;
    uint32_t x1 = x0 + T < w ? x0 + T : w, y1 = y0 + T < h ? y0 + T : h;
    uint32_t n = 0;
    for (uint32_t y = y0; y < y1; y++)
        for (uint32_t x = x0; x < x1; x++) {
            double *b = job->base + 3 * ((size_t)y * w + x);
            for (uint32_t i = 0; i < job->spp; i++) {
                il_vec3 base;
                if (il_ibl_camera_vertex(c, x, y, i, first, &slot[n], &base, &ts->rays))
                    n++;
                if (!first)
                    continue;
                if (!v3_is_finite(base)) {
                    ts->nonfinite++;
                    continue;
                }
                b[0] += base.x;
                b[1] += base.y;
                b[2] += base.z;
            }
        }
    if (job->cache)
        job->cache_count[t] = n;
    *count = n;
    return slot;
}

static inline void accumulate(double *acc, uint32_t pixel, il_vec3 c, il_ibl_tile_stats *ts)
{
    if (!v3_is_finite(c)) {
        ts->nonfinite++;
        return;
    }
    double *a = acc + 3 * (size_t)pixel;
    a[0] += c.x;
    a[1] += c.y;
    a[2] += c.z;
}

void il_ibl_shade_tile(const il_ibl_job *job, uint32_t t, bool first, uint32_t l0, uint32_t l1,
                       const il_ibl_shadow_maps *maps, il_ibl_scratch *sc, il_ibl_tile_stats *ts)
{
    uint32_t n = 0;
    const il_ibl_vertex *v = tile_vertices(job, t, first, sc, &n, ts);
    if (n == 0)
        return;
    const il_ibl_lights *ls = job->lights;
    const il_tracer *tr = job->cam.scene->tracer;
    for (uint32_t l = l0; l < l1; l++) {
        il_vec3 wi = ls->dir[l - ls->first], w = ls->weight[l - ls->first];
        if (v3_is_zero(w))
            continue;
        if (job->shadows == IL_IBL_SHADOW_RAYS) {
            uint32_t m = 0;
            for (uint32_t k = 0; k < n; k++) {
                il_vec3 fc = il_ibl_f_cos(&v[k], wi);
                if (v3_is_zero(fc))
                    continue;
                sc->rays[m] = (il_ray){.org = v[k].org, .tmin = 0.0f, .dir = wi, .tmax = INFINITY};
                sc->contrib[m] = v3_mul(fc, w);
                sc->pixel[m] = v[k].pixel;
                m++;
            }
            il_trace_visibility_n(tr, sc->rays, sc->visible, m);
            ts->shadow_rays += m;
            ts->rays += m;
            for (uint32_t j = 0; j < m; j++)
                if (sc->visible[j] > 0.0f)
                    accumulate(job->acc, sc->pixel[j], sc->visible[j] == 1.0f ? sc->contrib[j]
                                                       : v3_scale(sc->contrib[j], sc->visible[j]),
                               ts);
        } else {
            const il_ibl_shadow_map *map = maps ? &maps->maps[l - l0] : NULL;
            for (uint32_t k = 0; k < n; k++) {
                il_vec3 fc = il_ibl_f_cos(&v[k], wi);
                if (v3_is_zero(fc))
                    continue;
                float vis = map ? il_ibl_shadow_map_lookup(maps, map, &v[k]) : 1.0f;
                if (vis > 0.0f)
                    accumulate(job->acc, v[k].pixel, v3_scale(v3_mul(fc, w), vis), ts);
            }
        }
    }
}
