/* Camera samples: the ray through the pixel, followed through perfect
 * mirrors and glass (delta BSDFs, which no light can be sampled for) to the
 * first surface the lights shade.  Depth as in the path tracer: a
 * non-delta vertex after k delta bounces is shaded when k < max_depth, and
 * the environment or an emitter seen after k delta bounces counts when
 * k <= max_depth, so with max_depth 1 this is exactly the path tracer's
 * direct lighting (`--method pt --max-depth 1`) on non-specular scenes. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/ibl/ibl.h"
#include "scene/lights.h"

il_status il_ibl_camera_init(il_ibl_camera *c, const il_scene *scene, const il_render_desc *rd,
                             uint32_t width, uint32_t height, uint32_t max_depth, il_error *err)
{
    memset(c, 0, sizeof *c);
    c->scene = scene;
    c->ctx.width = width;
    c->ctx.height = height;
    c->ctx.seed = rd->seed;
    c->ctx.sampler = rd->sampler;
    c->ctx.filter = rd->filter;
    il_camera_init(&c->ctx.cam, &scene->camera.desc, width, height);
    c->max_depth = max_depth;

    /* The scene's lights other than the environment. */
    uint32_t n = scene->num_lights ? scene->num_lights : 1u;
    c->delta = il_malloc(n * sizeof(uint32_t), err);
    c->area = il_malloc(n * sizeof(uint32_t), err);
    float *power = il_malloc(n * sizeof(float), err);
    if (!c->delta || !c->area || !power) {
        free(power);
        il_ibl_camera_free(c);
        return IL_ERR_MEMORY;
    }
    for (uint32_t i = 0; i < scene->num_lights; i++) {
        const il_light *l = &scene->lights[i];
        if (l->kind == IL_LIGHTK_AREA) {
            power[c->num_area] = l->power;
            c->area[c->num_area++] = i;
        } else if (l->kind != IL_LIGHTK_ENVIRONMENT) {
            c->delta[c->num_delta++] = i;
        }
    }
    il_status st = IL_OK;
    if (c->num_area > 0)
        st = il_distrib1d_init(&c->area_pick, power, c->num_area, err);
    free(power);
    if (st != IL_OK)
        il_ibl_camera_free(c);
    return st;
}

void il_ibl_camera_free(il_ibl_camera *c)
{
    free(c->delta);
    free(c->area);
    il_distrib1d_free(&c->area_pick);
    c->delta = c->area = NULL;
    c->num_delta = c->num_area = 0;
}

/* Fills the vertex at a non-delta surface; false when wo grazes it (no
 * light can be reflected towards the camera). */
static bool make_vertex(const il_ibl_camera *c, const il_surface *s, const il_bsdf *b, il_vec3 wo,
                        il_vec3 beta, uint32_t pixel, il_ibl_vertex *v)
{
    float on = v3_dot(wo, s->ns), og = v3_dot(wo, s->ng);
    if (!(fabsf(on) > 1e-7f) || og == 0.0f)
        return false;
    v->n = on > 0.0f ? s->ns : v3_neg(s->ns);
    v->g = og > 0.0f ? s->ng : v3_neg(s->ng);
    v->org = il_offset_origin(c->scene->tracer, s->p, v->g, v->g);
    v->wo = wo;
    v->beta = beta;
    v->bsdf = *b;
    v->pixel = pixel;
    v->diffuse = b->type == IL_MATERIAL_DIFFUSE;
    v->kd = v3_scale(v3_mul(beta, b->diffuse), IL_INV_PI);
    return true;
}

bool il_ibl_camera_vertex(const il_ibl_camera *c, uint32_t x, uint32_t y, uint32_t i,
                          bool with_lights, il_ibl_vertex *v, il_vec3 *base, uint64_t *rays)
{
    const il_scene *s = c->scene;
    const il_tracer *tr = s->tracer;
    il_sampler smp;
    il_vec3 dir = il_camera_sample(&c->ctx, x, y, i, &smp);
    il_ray ray = {.org = c->ctx.cam.position, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    il_vec3 beta = v3s(1.0f), L = v3s(0.0f);
    bool found = false;
    for (uint32_t depth = 0;; depth++) {
        il_hit hit;
        (*rays)++;
        if (!il_trace_closest(tr, &ray, &hit)) {
            L = v3_add(L, v3_mul(beta, il_background_radiance(s, ray.dir)));
            break;
        }
        il_surface surf;
        il_scene_surface(s, hit.mesh, hit.prim, hit.b1, hit.b2, &surf);
        il_vec3 wo = v3_neg(ray.dir);
        if (!v3_is_zero(surf.material->emission))
            L = v3_add(L, v3_mul(beta, il_emitted_radiance(surf.material, surf.ng, wo)));
        if (depth >= c->max_depth)
            break;
        il_bsdf b;
        il_bsdf_init(&b, s, &surf);
        if (!il_bsdf_is_delta(&b)) {
            found = make_vertex(c, &surf, &b, wo, beta, y * c->ctx.width + x, v);
            if (found && with_lights && (c->num_delta > 0 || c->num_area > 0)) {
                il_vec2 u_pick = il_sampler_2d(&smp);
                il_vec2 u = il_sampler_2d(&smp);
                L = v3_add(L, il_ibl_other_lights(c, v, u_pick.x, u, rays));
            }
            break;
        }
        /* A delta bounce: the lobe (reflection or refraction) from the
         * sampler's next pair. */
        il_vec2 u = il_sampler_2d(&smp);
        il_bsdf_sample bs;
        if (!il_bsdf_sample_dir(&b, wo, u.x, v2(u.y, 0.5f), &bs) || !il_sides_agree(&surf, wo, bs.wi))
            break;
        beta = v3_mul(beta, bs.weight);
        if (v3_is_zero(beta) || !v3_is_finite(beta))
            break;
        ray = (il_ray){.org = il_offset_origin(tr, surf.p, surf.ng, bs.wi), .tmin = 0.0f,
                       .dir = bs.wi, .tmax = INFINITY};
    }
    *base = L;
    return found;
}
