/* One-sample direct lighting (next-event estimation without MIS). */
#include "scene/direct.h"

#include <math.h>

#include "scene/lights.h"
#include "trace/trace.h"

bool il_direct_light_sample(const il_scene *scene, const il_surface *s, const il_bsdf *b, il_vec3 wo,
                            float u_select, il_vec2 u, il_ray *shadow, il_vec3 *unblocked)
{
    il_light_sample ls;
    if (il_bsdf_is_delta(b) || !il_light_sample_at(scene, s->p, u_select, u, &ls) ||
        !il_sides_agree(s, wo, ls.wi) || !(ls.pdf > 0.0f))
        return false;
    float pdf_unused;
    il_vec3 f = il_bsdf_eval(b, wo, ls.wi, &pdf_unused);
    float cos_i = fabsf(v3_dot(ls.wi, b->frame.n));
    if (v3_is_zero(f) || cos_i <= 0.0f || v3_is_zero(ls.radiance))
        return false;
    const il_tracer *tr = scene->tracer;
    *shadow = isinf(ls.dist) ? (il_ray){.org = il_offset_origin(tr, s->p, s->ng, ls.wi), .tmin = 0.0f,
                                        .dir = ls.wi, .tmax = INFINITY}
                             : il_shadow_ray(tr, s->p, s->ng, ls.p, ls.n);
    *unblocked = v3_scale(v3_mul(f, ls.radiance), cos_i / ls.pdf);
    return true;
}

il_vec3 il_direct_light(const il_scene *scene, const il_surface *s, const il_bsdf *b, il_vec3 wo,
                        float u_select, il_vec2 u, uint64_t *rays)
{
    il_ray shadow;
    il_vec3 unblocked;
    if (!il_direct_light_sample(scene, s, b, wo, u_select, u, &shadow, &unblocked))
        return v3(0.0f, 0.0f, 0.0f);
    (*rays)++;
    float vis = il_trace_visibility(scene->tracer, &shadow);
    return vis == 1.0f ? unblocked : v3_scale(unblocked, vis);
}
