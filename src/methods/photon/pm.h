/* Photon mapping (`--method photon`) and stochastic progressive photon
 * mapping (`--method sppm`): the internals shared by the files of this
 * folder and the tests.  docs/photon-mapping.md explains the method, its
 * options and what it guarantees.
 *
 *   pm_photon.c    the 20-byte stored photon: packing and unpacking
 *   pm_kdtree.c    balanced kd-tree: k nearest neighbours, range queries
 *   pm_grid.c      hashed uniform grid: fixed-radius queries
 *   pm_map.c       a photon map: its photons and one of the two structures
 *   pm_estimate.c  radiance estimates from a map (filters, normal test)
 *   pm_irradiance.c precomputed irradiance at a subset of a map's photons
 *                  (Christensen 1999)
 *   ../light_emit.c emitting a photon from each kind of light (shared with
 *                  Linespace injection)
 *   pm_trace.c     following photons, filling the global and caustic maps
 *   pm_settings.c  the options: defaults, ranges, radii in scene units
 *   pm_path.c      camera (and gather) paths up to their first non-delta hit
 *   pm_render.c    the two-pass method: camera pass, final gather
 *   pm_sppm.c      stochastic progressive photon mapping
 */
#ifndef IL_METHODS_PM_H
#define IL_METHODS_PM_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#include "core/sampler.h"
#include "core/sampling.h"
#include "core/vec.h"
#include "illum/illum.h"
#include "methods/camera_pass.h"
#include "scene/bsdf.h"
#include "scene/scene.h"
#include "trace/trace.h"

/* ------------------------------------------------------------ the photon */

/* A stored photon: 20 bytes (Jensen 2001, 5.1 stores 20 too).
 *   p       where it landed
 *   power   RGB with a shared 8-bit exponent (Ward's RGBE), rounded to
 *           nearest; relative to the map's power_scale
 *   dir     unit direction towards where it came from, octahedral 8+8 bits
 *   normal  bits 0-13: the surface's geometric normal turned to the side
 *           the photon arrived from, octahedral 7+7 bits; bits 14-15: free
 *           for the search structure (the kd-tree's split axis) */
typedef struct il_photon {
    float p[3];
    uint32_t power;
    uint16_t dir;
    uint16_t normal;
} il_photon;

_Static_assert(sizeof(il_photon) == 20, "a stored photon is 20 bytes");

/* Packs a photon; power must be finite and non-negative. */
il_photon il_photon_pack(il_vec3 p, il_vec3 power, il_vec3 dir, il_vec3 normal);
il_vec3 il_photon_pos(const il_photon *ph);
il_vec3 il_photon_power(const il_photon *ph);   /* unscaled (multiply by the map's power_scale) */
il_vec3 il_photon_dir(const il_photon *ph);
il_vec3 il_photon_normal(const il_photon *ph);

/* The codecs on their own (for the tests). */
uint32_t il_rgbe_pack(il_vec3 c);
il_vec3 il_rgbe_unpack(uint32_t e);
uint16_t il_oct_pack(il_vec3 n, unsigned bits);   /* bits per component, at most 8 */
il_vec3 il_oct_unpack(uint16_t e, unsigned bits);

/* --------------------------------------------------------------- the map */

/* A photon map: the photons, reordered by the structure built over them. */
typedef struct il_pm_map {
    il_photon *photons;
    size_t count;
    float power_scale;         /* a photon's power is il_photon_power * power_scale */
    il_photon_lookup lookup;   /* which structure was built */
    /* The grid (pm_grid.c): photons sorted by cell, a hashed table of cells. */
    float cell_size;
    uint32_t hash_mask;        /* table size - 1 (a power of two) */
    uint32_t *cell_start;      /* hash_mask + 2 entries: photons of hash h are
                                  cell_start[h] .. cell_start[h+1]-1 */
    /* Precomputed irradiance (pm_irradiance.c; NULL until built): points at
     * every few photons, as stored photons in a kd-tree of their own: p the
     * photon's position, power the irradiance there in W/m^2 (already
     * scaled by power_scale), normal the photon's, dir unused. */
    il_photon *irr;
    size_t irr_count;
    float lo[3], hi[3];        /* the photons' bounding box (empty map: lo > hi) */
} il_pm_map;

/* Takes the photons (malloc'd, count of them; the map owns them from now on,
 * also on failure) and builds the chosen structure over them.  radius: the
 * grid's query radius (its cell size), ignored by the kd-tree.  An empty map
 * is valid: every query finds nothing. */
il_status il_pm_map_build(il_pm_map *map, il_photon *photons, size_t count, float power_scale,
                          il_photon_lookup lookup, float radius, il_error *err);
/* il_pm_map_build with a kd-tree's build split across the processes of d
 * (pm_kdtree.c; every process passes the same photons and gets the same
 * map); the grid is built on every process.  d off: il_pm_map_build. */
il_status il_pm_map_build_split(il_pm_map *map, il_photon *photons, size_t count, float power_scale,
                                il_photon_lookup lookup, float radius, const il_distrib *d,
                                il_error *err);
void il_pm_map_free(il_pm_map *map);
/* Bytes held by the photons and the structure. */
size_t il_pm_map_bytes(const il_pm_map *map);

typedef struct il_pm_neighbour {
    uint32_t index;            /* into map->photons */
    float d2;                  /* squared distance to the query point */
} il_pm_neighbour;

/* The k nearest photons within sqrt(max_d2) of p (kd-tree maps only),
 * into out[0..k-1], unordered; returns how many.  *r2 is the squared radius
 * of the estimate: the largest d2 found when k were found, else max_d2. */
uint32_t il_pm_knn(const il_pm_map *map, il_vec3 p, uint32_t k, float max_d2, il_pm_neighbour *out,
                   float *r2);

/* Every photon within sqrt(d2) of p (either structure; for the grid d2 may
 * not exceed the build radius squared), appended to a growing buffer. */
typedef struct il_pm_buffer {
    il_pm_neighbour *items;
    uint32_t count, cap;
} il_pm_buffer;
il_status il_pm_range(const il_pm_map *map, il_vec3 p, float d2, il_pm_buffer *out, il_error *err);
void il_pm_buffer_free(il_pm_buffer *b);

/* ------------------------------------------------------------ estimation */

typedef struct il_pm_lookup {
    il_photon_lookup lookup;   /* must match the map's */
    uint32_t k;                /* kd-tree: neighbours */
    float radius;              /* kd-tree: largest radius; grid: the radius */
    il_photon_filter filter;
} il_pm_lookup;

/* Per-thread scratch for il_pm_estimate (the neighbour buffers). */
typedef struct il_pm_scratch {
    il_pm_neighbour *knn;      /* k entries */
    uint32_t knn_cap;
    il_pm_buffer range;
} il_pm_scratch;
void il_pm_scratch_free(il_pm_scratch *s);

/* Reflected radiance at a surface point towards wo from the photons near it
 * (Jensen 2001, eq. 7.6, with the filter of 7.2): sum over the photons of
 * f(wo, wi_p) * power_p * w_p / (norm * pi * r^2).  n is the query's
 * geometric normal turned to wo's side; photons whose stored normal
 * disagrees with it (a corner, the other side of a thin wall) or that lie
 * off its tangent plane (a parallel surface just behind it) are skipped
 * (il_pm_on_surface in pm_internal.h).
 * Returns zero for an empty map.  Fails only when out of memory. */
il_status il_pm_estimate(const il_pm_map *map, const il_pm_lookup *q, const il_bsdf *bsdf,
                         il_vec3 p, il_vec3 n, il_vec3 wo, il_pm_scratch *scratch, il_vec3 *out,
                         il_error *err);

/* The cosine a photon's normal must have with the query's to count. */
#define IL_PM_NORMAL_COS 0.9f
/* How far off the query's tangent plane a photon may lie, as a share of the
 * search radius, beyond what the surface's bend explains
 * (il_pm_on_surface in pm_internal.h). */
#define IL_PM_DISC_THICKNESS 0.1f

/* Irradiance at p on a surface facing n (Jensen 2001, eq. 7.6 with f = 1):
 * sum over the photons passing the normal test and arriving from n's side
 * of power_p * w_p / (norm * pi * r^2), the same photons, filter and radius
 * as il_pm_estimate.  A Lambertian surface of albedo rho reflects
 * rho/pi * E.  Fails only when out of memory. */
il_status il_pm_irradiance_estimate(const il_pm_map *map, const il_pm_lookup *q, il_vec3 p,
                                    il_vec3 n, il_pm_scratch *scratch, il_vec3 *out, il_error *err);

/* ------------------------------------------- precomputed irradiance */

/* Christensen 1999 ("Faster Photon Map Global Illumination", JGT 4(3)):
 * the irradiance estimate at every `stride`-th photon of the map (in the
 * map's order), computed in parallel on `threads` threads (0: all cores),
 * into map->irr with a kd-tree over it.  The values do not depend on the
 * thread count.  q is the lookup the estimates use (as the render's). */
#define IL_PM_IRRADIANCE_STRIDE 4u
il_status il_pm_irradiance_build(il_pm_map *map, const il_pm_lookup *q, uint32_t stride,
                                 int threads, il_error *err);

/* The precomputed irradiance of the nearest point within sqrt(max_d2) of p
 * whose normal agrees with n (IL_PM_NORMAL_COS) into *E; false (and *E
 * zero) when there is none or nothing was precomputed. */
bool il_pm_irradiance_lookup(const il_pm_map *map, il_vec3 p, il_vec3 n, float max_d2, il_vec3 *E);

/* Reflected radiance from the global map at a camera or gather vertex:
 * the precomputed irradiance times albedo/pi at a Lambertian surface when
 * the map has it, il_pm_estimate otherwise. */
il_status il_pm_estimate_global(const il_pm_map *map, const il_pm_lookup *q, const il_bsdf *bsdf,
                                il_vec3 p, il_vec3 n, il_vec3 wo, il_pm_scratch *scratch,
                                il_vec3 *out, il_error *err);

/* --------------------------------------------------------------- tracing */

/* What a photon leaves at a non-delta surface after at least one bounce
 * (direct light is left to shadow rays). */
typedef struct il_pm_deposit {
    il_vec3 p;
    il_vec3 n;                 /* geometric normal turned to the side it came from */
    il_vec3 wi;                /* unit, towards where it came from */
    il_vec3 power;             /* W, as if this one photon carried the whole
                                  emission: divide by the photons emitted */
    bool caustic;              /* only delta bounces since the light (L S+ D) */
} il_pm_deposit;

typedef void (*il_pm_deposit_fn)(void *user, const il_pm_deposit *d);

/* Emits photon `index` (the lights chosen by scene->light_pmf; with
 * at_portals, the light paths split at the portals, methods/portal_light.h)
 * and follows it for at most max_depth bounces, Russian roulette by the
 * surface's albedo; calls deposit at every stored hit.  Its path depends
 * only on (seed, index).  Returns the rays it cast. */
uint64_t il_pm_trace_photon(const il_scene *scene, uint64_t seed, uint64_t index,
                            uint32_t max_depth, bool at_portals, il_pm_deposit_fn deposit, void *user);

/* il_photon_desc.on_step during PHOTON's set-up (pm_watch.c). */
typedef struct il_pm_watch {
    il_photon_step_fn fn;      /* NULL: no reports, no stop */
    void *user;
    double t0;                 /* omp_get_wtime when the set-up started */
    bool stopped;              /* fn returned false */
} il_pm_watch;

/* Reports progress to w->fn (w may be NULL); returns false, and sets
 * w->stopped, once it asked to stop.  Calling thread only. */
bool il_pm_watch_report(il_pm_watch *w, il_photon_phase phase, uint64_t done, uint64_t total);

typedef struct il_pm_trace_desc {
    uint64_t first;            /* photon indices first .. first+count-1 */
    uint64_t count;
    uint64_t seed;
    uint32_t max_depth;
    int threads;               /* 0: all cores */
    bool split;                /* true: caustic photons to *caustic, the rest to
                                  *global; false: all to *global (SPPM) */
    bool at_portals;           /* split the light paths at the scene's portals
                                  (methods/portal_light.h) */
    il_pm_watch *watch;        /* reports after every round of chunks, and may stop
                                  the tracing there; NULL: none */
} il_pm_trace_desc;

typedef struct il_pm_photons {
    il_photon *global;  size_t num_global;
    il_photon *caustic; size_t num_caustic;
    uint64_t rays;
    uint64_t emitted;   /* photons traced: desc->count unless the watch stopped it,
                           then the first `emitted` indices */
} il_pm_photons;

/* Traces the photons in parallel; the arrays are the same, in the same
 * order, whatever the thread count (photons in index order).  The caller
 * frees the arrays (or hands them to il_pm_map_build). */
il_status il_pm_trace(const il_scene *scene, const il_pm_trace_desc *desc, il_pm_photons *out,
                      il_error *err);
/* Hands the photons' positions to d->on_photons when it is set (d may be
 * NULL); without memory for the copy it is not called. */
void il_pm_report_photons(const il_photon_desc *d, const il_photon *photons, size_t n, int which);

/* ------------------------------------------------------------- rendering */

/* Where a camera (or gather) path first meets a surface that is not a
 * mirror or glass: the point the photon estimates are read at. */
typedef struct il_pm_vertex {
    il_surface s;
    il_bsdf bsdf;
    il_vec3 wo;                /* unit, back along the path */
    il_vec3 n;                 /* geometric normal turned to wo's side */
    il_vec3 beta;              /* throughput of the delta bounces before it */
    uint32_t depth;            /* delta bounces before it */
} il_pm_vertex;

/* Follows the ray through delta bounces (drawing their lobes from smp) to
 * its first non-delta hit, at most max_depth bounces.  With emitted != NULL
 * (camera rays only) it adds the light of emitters and the background
 * (il_background_radiance: the sky and the sun's disc) met on the way, seen
 * directly or through delta bounces, to *emitted, times the throughput.
 * False when the path leaves the scene, is absorbed or runs out of depth. */
bool il_pm_trace_to_diffuse(const il_scene *scene, il_ray ray, il_sampler *smp, uint32_t max_depth,
                            il_vec3 *emitted, il_pm_vertex *out, uint64_t *rays);

/* Defaults resolved from an il_photon_desc (NULL: all defaults), radii in
 * scene units. */
typedef struct il_pm_settings {
    uint64_t photons;
    il_pm_lookup lookup;
    uint32_t final_gather;
    float alpha;
    float initial_radius;
    uint32_t max_photon_depth;
    float size;                /* the scene's size the radii are fractions of */
    bool portal_light;         /* split the light paths at the portals (not
                                  il_photon_desc.no_portal_light, and
                                  il_portal_light_wanted) */
} il_pm_settings;
il_status il_pm_settings_resolve(const il_scene *scene, const il_photon_desc *d, uint32_t max_depth,
                                 bool sppm, il_pm_settings *out, il_error *err);

/* ------------------------------------- split across processes (pm_distrib.c) */

/* il_pm_trace when d is off; otherwise this process traces its part of the
 * index range and the parts are exchanged: every process gets the arrays
 * il_pm_trace gives for the whole range, byte for byte (out->rays counts
 * this process's rays only). */
il_status il_pm_trace_split(const il_scene *scene, const il_pm_trace_desc *desc,
                            const il_distrib *d, il_pm_photons *out, il_error *err);
/* il_pm_irradiance_build with the points split across the processes of d
 * (contiguous ranges) and exchanged: the same map->irr on every process,
 * byte for byte, as il_pm_irradiance_build's.  d off: il_pm_irradiance_build. */
/* A watch (NULL: none) hears of the points computed and may stop the
 * build: map->irr is then left empty (full estimates are made instead). */
il_status il_pm_irradiance_build_split(il_pm_map *map, const il_pm_lookup *q, uint32_t stride,
                                       int threads, const il_distrib *d, il_pm_watch *watch,
                                       il_error *err);

il_status il_pm_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_render_stats *stats, il_error *err);
il_status il_sppm_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                         il_render_stats *stats, il_error *err);

#endif
