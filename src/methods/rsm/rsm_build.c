/* Building the reflective shadow maps: one texel = one ray from the light
 * (Dachsbacher & Stamminger 2005, section 3, rendered here by ray casting
 * through Embree instead of rasterising).  Units and the flux of a texel:
 * docs/rsm.md, "The maps".  */
#include <math.h>
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/rsm/rsm.h"
#include "trace/trace.h"

/* Grazing texels: the footprint A_p = dw d^2 / cos grows without bound as
 * cos -> 0; below this cosine it is kept at the value there. */
#define RSM_MIN_COS 0.01f

/* Intensity (W/sr) of a point or spot light towards unit direction d, the
 * profile of lights.c (pbrt-v4 12.1): I cos^n(theta) inside the cut-off. */
static il_vec3 intensity_towards(const il_light *l, il_vec3 d)
{
    if (l->kind != IL_LIGHTK_SPOT)
        return l->intensity;
    float c = v3_dot(l->direction, d);
    if (c < l->cos_cutoff)
        return v3s(0.0f);
    float scale = 1.0f;
    if (l->spot_exponent > 0.0f) {
        if (c <= 0.0f)
            return v3s(0.0f);
        scale = powf(c, l->spot_exponent);
    }
    return v3_scale(l->intensity, scale);
}

/* The texel's ray and the flux (W) it carries: perspective, flux = I(w) dw
 * with dw = (2 half / size)^2 cos^3(alpha) the solid angle of a texel of the
 * image plane at distance 1 seen at angle alpha off the axis; orthographic,
 * flux = E A_perp with A_perp = (2 half / size)^2.  *dw_or_area is dw or
 * A_perp. */
static il_vec3 texel_ray(const il_rsm_map *m, const il_light *l, float reach, uint32_t i, uint32_t j,
                         il_ray *ray, float *dw_or_area)
{
    float step = 2.0f * m->half / (float)m->size;
    float a = ((float)i + 0.5f) * step - m->half;
    float b = ((float)j + 0.5f) * step - m->half;
    il_vec3 across = v3_add(v3_scale(m->u, a), v3_scale(m->v, b));
    if (m->ortho) {
        *ray = (il_ray){.org = v3_fma(v3_add(m->org, across), m->w, -reach), .tmin = 0.0f,
                        .dir = m->w, .tmax = INFINITY};
        *dw_or_area = step * step;
        return v3_scale(l->intensity, step * step);
    }
    il_vec3 dir = v3_add(m->w, across);
    float inv_len = 1.0f / v3_length(dir);
    *ray = (il_ray){.org = m->org, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    float dw = step * step * inv_len * inv_len * inv_len;
    *dw_or_area = dw;
    return v3_scale(intensity_towards(l, v3_scale(dir, inv_len)), dw);
}

/* Ray casts every texel of map m. */
static void fill_map(const il_scene *scene, il_rsm_map *m, int threads, uint64_t *rays)
{
    const il_light *l = &scene->lights[m->light];
    const il_tracer *tr = scene->tracer;
    float reach = 2.0f * scene->scene_radius + 1.0f;
    uint32_t size = m->size;
    uint64_t texels = 0, cast = 0;
    int nt = threads > 0 ? threads : omp_get_max_threads();
#pragma omp parallel for schedule(dynamic, 4) num_threads(nt) reduction(+ : texels, cast)
    for (uint32_t j = 0; j < size; j++) {
        for (uint32_t i = 0; i < size; i++) {
            il_rsm_texel *t = &m->tex[(size_t)j * size + i];
            memset(t, 0, sizeof *t);
            il_ray ray;
            float dw;
            il_vec3 flux = texel_ray(m, l, reach, i, j, &ray, &dw);
            if (v3_is_zero(flux))
                continue;
            il_hit hit;
            cast++;
            if (!il_trace_closest(tr, &ray, &hit))
                continue;
            il_surface s;
            il_scene_surface(scene, hit.mesh, hit.prim, hit.b1, hit.b2, &s);
            il_bsdf b;
            il_bsdf_init(&b, scene, &s);
            if (il_bsdf_is_delta(&b) || v3_is_zero(b.diffuse))
                continue;
            float len = v3_length(ray.dir);
            il_vec3 to_light = v3_scale(ray.dir, -1.0f / len);
            float cos_g = v3_dot(s.ng, to_light);
            il_vec3 n = s.ns;
            if (cos_g < 0.0f) {
                cos_g = -cos_g;
                n = v3_neg(n);
            }
            /* The texel's footprint on the surface: its solid angle times
             * d^2 (or its orthographic area) over the cosine of incidence. */
            float d = hit.t * len;
            float area_perp = m->ortho ? dw : dw * d * d;
            t->p = v3_fma(ray.org, ray.dir, hit.t);
            t->n = n;
            t->area = area_perp / fmaxf(cos_g, RSM_MIN_COS);
            /* Phi_p: the flux reaching the surface times its diffuse albedo
             * (Dachsbacher & Stamminger 2005, section 3). */
            t->flux = v3_mul(flux, b.diffuse);
            texels++;
        }
    }
    m->texels = texels;
    *rays += cast;
}

/* Room for one more map, its texels allocated. */
static il_rsm_map *add_map(il_rsm *r, uint32_t size, il_error *err)
{
    il_rsm_map *grown = realloc(r->maps, (r->count + 1) * sizeof *grown);
    if (!grown) {
        il_fail(err, IL_ERR_MEMORY, "rsm: out of memory for the maps");
        return NULL;
    }
    r->maps = grown;
    il_rsm_map *m = &r->maps[r->count];
    memset(m, 0, sizeof *m);
    m->size = size;
    m->tex = il_malloc((size_t)size * size * sizeof(il_rsm_texel), err);
    if (!m->tex)
        return NULL;
    r->count++;
    return m;
}

/* Builds map m and keeps it when some texel holds flux. */
static void finish_map(const il_scene *scene, il_rsm *r, int threads)
{
    il_rsm_map *m = &r->maps[r->count - 1];
    fill_map(scene, m, threads, &r->rays);
    if (m->texels == 0) {
        free(m->tex);
        r->count--;
    }
}

il_status il_rsm_build(const il_scene *scene, uint32_t resolution, int threads, il_rsm *out,
                       il_error *err)
{
    memset(out, 0, sizeof *out);
    for (uint32_t li = 0; li < scene->num_lights; li++) {
        const il_light *l = &scene->lights[li];
        bool cube = l->kind == IL_LIGHTK_POINT;
        if (l->kind == IL_LIGHTK_SPOT)
            cube = l->cos_cutoff < cosf(IL_RSM_MAX_SPOT_ANGLE * IL_PI / 180.0f);
        if (l->kind == IL_LIGHTK_SPOT && !cube) {
            /* One perspective map around the spot's axis, its half field the
             * cut-off angle. */
            il_rsm_map *m = add_map(out, resolution, err);
            if (!m)
                goto fail;
            il_frame f = il_frame_from_normal(l->direction);
            m->org = l->position;
            m->u = f.s;
            m->v = f.t;
            m->w = l->direction;
            float s = sqrtf(fmaxf(0.0f, 1.0f - l->cos_cutoff * l->cos_cutoff));
            m->half = s / l->cos_cutoff;
            m->light = li;
            finish_map(scene, out, threads);
        } else if (cube) {
            /* Six faces of a cube around the light, each a 90-degree
             * frustum; u and v along the cube's other axes so that the
             * faces tile the sphere of directions. */
            for (int k = 0; k < 6; k++) {
                il_rsm_map *m = add_map(out, resolution, err);
                if (!m)
                    goto fail;
                float e[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
                int axis = k >> 1;
                float sign = (k & 1) ? -1.0f : 1.0f;
                const float *a = e[axis], *b = e[(axis + 1) % 3], *c = e[(axis + 2) % 3];
                m->org = l->position;
                m->w = v3(sign * a[0], sign * a[1], sign * a[2]);
                m->u = v3(b[0], b[1], b[2]);
                m->v = v3(c[0], c[1], c[2]);
                m->half = 1.0f;
                m->light = li;
                finish_map(scene, out, threads);
            }
        } else if (l->kind == IL_LIGHTK_DIRECTIONAL) {
            /* An orthographic map over the scene's bounding sphere. */
            il_rsm_map *m = add_map(out, resolution, err);
            if (!m)
                goto fail;
            il_frame f = il_frame_from_normal(l->direction);
            m->ortho = true;
            m->org = scene->scene_center;
            m->u = f.s;
            m->v = f.t;
            m->w = l->direction;
            m->half = scene->scene_radius;
            m->light = li;
            finish_map(scene, out, threads);
        }
    }
    return IL_OK;
fail:
    il_rsm_free(out);
    return err ? err->status : IL_ERR_MEMORY;
}

void il_rsm_free(il_rsm *r)
{
    for (uint32_t k = 0; k < r->count; k++)
        free(r->maps[k].tex);
    free(r->maps);
    il_distrib1d_free(&r->choice);
    memset(r, 0, sizeof *r);
}

uint64_t il_rsm_bytes(const il_rsm *r)
{
    uint64_t b = (uint64_t)r->count * sizeof(il_rsm_map);
    for (uint32_t k = 0; k < r->count; k++)
        b += (uint64_t)r->maps[k].size * r->maps[k].size * sizeof(il_rsm_texel);
    return b;
}
