/* The work of one render of the ibl method, shared by the driver
 * (ibl_render.c) and the tile shader (ibl_shade.c). */
#ifndef IL_METHODS_IBL_SHADE_H
#define IL_METHODS_IBL_SHADE_H

#include "methods/ibl/ibl.h"

typedef struct il_ibl_job {
    il_ibl_camera cam;
    const il_ibl_lights *lights;
    il_ibl_shadows shadows;
    uint32_t spp;
    uint32_t tile;             /* tile side in pixels */
    uint32_t tiles_x, tiles;
    uint32_t tile_samples;     /* tile * tile * spp: most vertices of a tile */
    il_ibl_vertex *cache;      /* tile_samples per tile, or NULL: traced again per pass */
    uint32_t *cache_count;     /* vertices per tile in the cache */
    double *base;              /* 3 per pixel: sum over samples of what the lights do not add */
    double *acc;               /* 3 per pixel: sum over samples and lights of f L cos V / pdf */
} il_ibl_job;

/* One thread's memory: room for a tile's vertices and one light's rays. */
typedef struct il_ibl_scratch {
    il_ibl_vertex *vertices;
    il_ray *rays;
    il_vec3 *contrib;
    uint32_t *pixel;
    float *visible;
} il_ibl_scratch;

typedef struct il_ibl_tile_stats {
    uint64_t rays;             /* all rays */
    uint64_t shadow_rays;      /* the environment lights' shadow rays */
    uint64_t nonfinite;
} il_ibl_tile_stats;

/* Shades tile t with lights l0..l1-1 (maps: their shadow maps, map k for
 * light l0 + k, when shadows are maps).  `first`: the first pass over the
 * tile, which traces the camera samples and adds their base terms. */
void il_ibl_shade_tile(const il_ibl_job *job, uint32_t t, bool first, uint32_t l0, uint32_t l1,
                       const il_ibl_shadow_maps *maps, il_ibl_scratch *sc, il_ibl_tile_stats *ts);

#endif
