/* The scene's lights other than the environment, so that a scene lit by a
 * map and a lamp renders as the path tracer renders it: point, spot and
 * directional lights are delta lights, evaluated exactly (each one, with a
 * shadow ray: they are directional lights of the many-light set that need
 * no sampling); emissive triangles are sampled, one point on one emitter
 * chosen by power per camera sample (pbrt-v4 12.6.2 and 12.2; the sample
 * and its density come from il_light_sample_at, asked for that light). */
#include "methods/ibl/ibl.h"
#include "scene/lights.h"

/* il_light_sample_at for light li of the scene's table: u_select = cdf[li]
 * picks it whenever its selection bin has any width in float (a light
 * too faint for that is never picked by the path tracer either).  *pdf is
 * the sample's density without the table's selection probability. */
static bool sample_light(const il_scene *s, uint32_t li, il_vec3 p, il_vec2 u, il_light_sample *ls,
                         float *pdf)
{
    if (!il_light_sample_at(s, p, s->light_cdf[li], u, ls) || ls->light != li)
        return false;
    float pmf = s->light_pmf[li];
    *pdf = ls->pdf / pmf;
    return pmf > 0.0f && *pdf > 0.0f && isfinite(*pdf);
}

/* The part of contribution c that the shadow ray from the vertex towards
 * the sample lets through (il_trace_visibility). */
static il_vec3 visible_part(const il_scene *s, const il_ibl_vertex *v, const il_light_sample *ls,
                            il_vec3 c, uint64_t *rays)
{
    if (v3_is_zero(c) || !v3_is_finite(c))
        return v3s(0.0f);
    const il_tracer *tr = s->tracer;
    il_ray r;
    if (isinf(ls->dist))
        r = (il_ray){.org = v->org, .tmin = 0.0f, .dir = ls->wi, .tmax = INFINITY};
    else
        r = il_shadow_ray(tr, v->org, v->g, ls->p, ls->n);
    (*rays)++;
    return v3_scale(c, il_trace_visibility(tr, &r));
}

il_vec3 il_ibl_other_lights(const il_ibl_camera *c, const il_ibl_vertex *v, float u_select,
                            il_vec2 u, uint64_t *rays)
{
    const il_scene *s = c->scene;
    il_vec3 L = v3s(0.0f);
    il_light_sample ls;
    float pdf;
    for (uint32_t k = 0; k < c->num_delta; k++) {
        /* Delta lights: the "sample" is the light itself, pdf 1. */
        if (!sample_light(s, c->delta[k], v->org, v2(0.5f, 0.5f), &ls, &pdf))
            continue;
        il_vec3 f = il_ibl_f_cos(v, ls.wi);
        L = v3_add(L, visible_part(s, v, &ls, v3_scale(v3_mul(f, ls.radiance), 1.0f / pdf), rays));
    }
    if (c->num_area > 0) {
        float pick;
        uint32_t j = il_distrib1d_sample_discrete(&c->area_pick, u_select, &pick, NULL);
        if (pick > 0.0f && sample_light(s, c->area[j], v->org, u, &ls, &pdf)) {
            il_vec3 f = il_ibl_f_cos(v, ls.wi);
            L = v3_add(L, visible_part(s, v, &ls, v3_scale(v3_mul(f, ls.radiance), 1.0f / (pick * pdf)),
                                     rays));
        }
    }
    return L;
}
