/* Helpers for the radiosity validation tests: box rooms built through the
 * public API, and the solver pipeline run step by step through rad.h. */
#ifndef IL_TESTS_RAD_SCENES_H
#define IL_TESTS_RAD_SCENES_H

#include <stdlib.h>
#include <string.h>

#include "pt_scenes.h"
#include "methods/radiosity/rad.h"

static inline uint32_t diffuse_material(il_scene *s, il_vec3 rho, il_vec3 emission)
{
    il_material_desc d = {.type = IL_MATERIAL_DIFFUSE, .diffuse = rho, .emission = emission};
    return add_material(s, d);
}

/* The six inward-facing walls of the box [0,size]^3; mat[0..5] are floor
 * (y=0), ceiling (y=size), x=0, x=size, z=0, z=size. */
static inline void add_box_room(il_scene *s, float size, const uint32_t mat[6])
{
    float h = 0.5f * size;
    add_quad(s, v3(h, 0, h), v3(0, 0, h), v3(h, 0, 0), mat[0]);
    add_quad(s, v3(h, size, h), v3(h, 0, 0), v3(0, 0, h), mat[1]);
    add_quad(s, v3(0, h, h), v3(0, h, 0), v3(0, 0, h), mat[2]);
    add_quad(s, v3(size, h, h), v3(0, 0, h), v3(0, h, 0), mat[3]);
    add_quad(s, v3(h, h, 0), v3(h, 0, 0), v3(0, h, 0), mat[4]);
    add_quad(s, v3(h, h, size), v3(0, h, 0), v3(h, 0, 0), mat[5]);
}

/* A 1 m room: grey floor and ceiling, red x=0 wall, green x=1 wall, grey
 * back and front, and a 0.3 m square lamp facing down just below the ceiling. */
static inline il_scene *coloured_room(void)
{
    il_scene *s = new_scene();
    uint32_t grey = diffuse_material(s, v3(0.7f, 0.7f, 0.7f), v3s(0));
    uint32_t red = diffuse_material(s, v3(0.75f, 0.15f, 0.1f), v3s(0));
    uint32_t green = diffuse_material(s, v3(0.1f, 0.6f, 0.15f), v3s(0));
    uint32_t lamp = diffuse_material(s, v3(0.5f, 0.5f, 0.5f), v3(8.0f, 7.5f, 6.5f));
    const uint32_t mat[6] = {grey, grey, red, green, grey, grey};
    add_box_room(s, 1.0f, mat);
    add_quad(s, v3(0.5f, 0.98f, 0.5f), v3(0.15f, 0, 0), v3(0, 0, 0.15f), lamp);
    return s;
}

/* The pipeline of il_rad_run, step by step, so tests can change settings
 * that il_radiosity_desc cannot express (a cache cap in bytes). */
typedef struct rad_case {
    il_rad_settings set;
    il_patch_mesh *mesh;
    il_rad_solution sol;
    il_radiosity_stats stats;
} rad_case;

/* cache_bytes: 0 keeps the resolved cap. */
static inline il_status rad_case_run(const il_scene *s, const il_render_desc *rd, size_t cache_bytes,
                                     rad_case *c)
{
    memset(c, 0, sizeof *c);
    il_status st = il_rad_settings_resolve(s, rd, &c->set, &g_err);
    if (st != IL_OK)
        return st;
    if (cache_bytes)
        c->set.ff_cache_bytes = cache_bytes;
    st = il_patch_mesh_build(s, &(il_patch_sizing){c->set.patch_size, c->set.subdivisions}, &c->mesh, &g_err);
    if (st != IL_OK)
        return st;
    st = il_rad_solution_init(&c->sol, c->mesh->num_patches, &g_err);
    if (st != IL_OK)
        return st;
    st = il_rad_direct(s, c->mesh, &c->set, &c->sol, &g_err);
    if (st != IL_OK)
        return st;
    il_ff *ff = NULL;
    il_ff_cache *cache = NULL;
    st = il_ff_create(c->mesh, &c->set, &ff, &g_err);
    if (st == IL_OK)
        st = il_ff_cache_create(c->mesh->num_patches, c->set.ff_cache_bytes, &cache, &g_err);
    if (st == IL_OK)
        st = il_rad_solve(c->mesh, ff, cache, &c->set, &c->sol, &c->stats, &g_err);
    if (cache)
        il_ff_cache_release(cache);
    if (ff)
        il_ff_release(ff);
    return st;
}

static inline void rad_case_free(rad_case *c)
{
    il_rad_solution_free(&c->sol);
    if (c->mesh)
        il_patch_mesh_release(c->mesh);
    memset(c, 0, sizeof *c);
}

/* sum_i A_i lum(|a_i - b_i|) / sum_i A_i lum(b_i). */
static inline double rad_power_diff(const il_patch_mesh *m, const il_vec3 *a, const il_vec3 *b)
{
    double num = 0.0, den = 0.0;
    for (uint32_t i = 0; i < m->num_patches; i++) {
        il_vec3 d = v3_sub(a[i], b[i]);
        d = v3(fabsf(d.x), fabsf(d.y), fabsf(d.z));
        num += m->patches[i].area * il_luminance(d);
        den += m->patches[i].area * il_luminance(b[i]);
    }
    return den > 0.0 ? num / den : num;
}

/* The largest per-patch, per-channel relative difference (to max(|b|, floor)). */
static inline double rad_max_rel_diff(const il_patch_mesh *m, const il_vec3 *a, const il_vec3 *b,
                                      double floor)
{
    double worst = 0.0;
    for (uint32_t i = 0; i < m->num_patches; i++)
        for (int c = 0; c < 3; c++) {
            double x = v3_get(a[i], c), y = v3_get(b[i], c);
            double r = fabs(x - y) / fmax(fabs(y), floor);
            if (r > worst)
                worst = r;
        }
    return worst;
}

#endif
