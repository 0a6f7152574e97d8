/* One path: the radiance estimator of the path tracer.
 *
 * Unidirectional path tracing (Kajiya 1986) in the form of pbrt-v4's
 * PathIntegrator (13.4): at each vertex, next-event estimation (one light
 * sample and a shadow ray) plus BSDF sampling to continue the path; an
 * emitter found either way is weighted by the power heuristic (Veach 1997,
 * 9.2.4) so the two strategies combine without double counting.  Delta
 * lights can only be reached by NEE and delta BSDFs only by BSDF sampling:
 * both keep weight 1. */
#include <math.h>

#include "core/sampling.h"
#include "methods/pt/pt.h"
#include "scene/bsdf.h"
#include "scene/lights.h"
#include "trace/trace.h"

/* The weight of a sample of technique `own` (IL_PT_NEE_ONLY: light
 * sampling, IL_PT_BSDF_ONLY: BSDF sampling) with density own_pdf, when the
 * other technique has density other_pdf: the power heuristic under MIS,
 * else 1 for the technique in use and 0 for the other. */
static float mis_weight(il_pt_strategy strategy, il_pt_strategy own, float own_pdf, float other_pdf)
{
    if (strategy == IL_PT_MIS)
        return il_power_heuristic(own_pdf, other_pdf);
    return strategy == own ? 1.0f : 0.0f;
}

static inline il_vec3 add_scaled(il_vec3 acc, il_vec3 beta, il_vec3 value, float w)
{
    return v3_add(acc, v3_scale(v3_mul(beta, value), w));
}

void il_pt_begin(il_pt_state *st, il_vec3 org, il_vec3 dir)
{
    st->L = v3s(0.0f);
    st->beta = v3s(1.0f);
    st->specular = true;          /* camera rays see emitters at full weight */
    st->camera_chain = true;
    st->prev_pdf = 0.0f;
    st->prev_p = org;
    st->depth = 0;
    st->ray = (il_ray){.org = org, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    st->shadow = false;
    st->rays = 1;                 /* the camera ray */
}

bool il_pt_step(const il_scene *s, il_pt_state *st, const il_hit *hit, il_sampler *smp,
                uint32_t max_depth, il_pt_strategy strategy)
{
    il_surface surf;
    if (hit)
        il_scene_surface(s, hit->mesh, hit->prim, hit->b1, hit->b2, &surf);
    return il_pt_step_at(s, st, hit, hit ? &surf : NULL, NULL, smp, max_depth, strategy);
}

bool il_pt_step_at(const il_scene *s, il_pt_state *st, const il_hit *hit, const il_surface *sp,
                   const il_pt_drawn *drawn, il_sampler *smp, uint32_t max_depth,
                   il_pt_strategy strategy)
{
    const il_tracer *tr = s->tracer;
    st->shadow = false;
    if (!hit) {
        /* A camera or specular ray takes the sky at weight 1 (and the sun's
         * disc, when the camera sees it); a BSDF ray weighs the sky against
         * light sampling's density (one lookup for both). */
        float light_pdf = 0.0f;
        il_vec3 le = st->camera_chain ? il_background_radiance(s, st->ray.dir)
                     : st->specular   ? il_environment_radiance(s, st->ray.dir)
                                      : il_environment_light_eval(s, st->prev_p, st->ray.dir, &light_pdf);
        if (!v3_is_zero(le)) {
            float w = st->specular ? 1.0f : mis_weight(strategy, IL_PT_BSDF_ONLY, st->prev_pdf, light_pdf);
            st->L = add_scaled(st->L, st->beta, le, w);
        }
        return false;
    }
    /* `depth` counts the scattering events before the current ray. */
    uint32_t depth = st->depth;
    const il_surface surf = *sp;
    il_vec3 wo = v3_neg(st->ray.dir);
    const il_material *m = surf.material;

    /* An emitter found by the camera ray or by BSDF sampling. */
    if (!v3_is_zero(m->emission)) {
        il_vec3 le = il_emitted_radiance(m, surf.ng, wo);
        if (!v3_is_zero(le)) {
            float w = 1.0f;
            if (!st->specular) {
                uint32_t light = s->triangle_light[hit->mesh][hit->prim];
                w = mis_weight(strategy, IL_PT_BSDF_ONLY, st->prev_pdf,
                               il_light_pdf_area(s, light, st->prev_p, surf.p, surf.ng));
            }
            st->L = add_scaled(st->L, st->beta, le, w);
        }
    }
    /* max_depth scattering events (bounces) at most: after the last one
     * only its BSDF-sampled emitter hit above is still counted, so
     * max_depth 1 is exactly direct lighting (pbrt-v4's maxdepth). */
    if (depth >= max_depth)
        return false;

    /* A vertex whose light sample and next ray a wave already made
     * (il_diffuse_wave) needs no BSDF of its own; one with either made
     * takes it from there. */
    const il_diffuse_out *made = drawn ? &drawn->diffuse : NULL;
    bool nee_done = made && made->nee_done, next_done = made && made->next_done;
    il_bsdf b;
    if (!(nee_done && next_done))
        il_bsdf_init(&b, s, &surf);
    /* The sample dimensions are drawn in the same order at every vertex,
     * whatever happens, so a vertex's numbers never depend on branches
     * (the roulette number, drawn last, only from the fourth bounce on).
     * The light choice and the BSDF lobe choice share one pair. */
    il_vec2 u_own[3];
    const il_vec2 *u = drawn ? drawn->u : NULL;
    if (!u) {
        il_sampler_2d_n(smp, u_own, 3);
        u = u_own;
    }
    il_vec2 u_choice = u[0], u_light = u[1], u_bsdf = u[2];
    float u_select = u_choice.x, u_lobe = u_choice.y;

    /* Next-event estimation: a light sample and a shadow ray, which the
     * caller traces; its contribution is added when nothing blocks it. */
    il_light_sample ls;
    if (nee_done) {
        if (made->shadow) {
            st->shadow_ray = made->shadow_ray;
            st->shadow = true;
            st->rays++;
            st->shadow_L = made->shadow_L;
        }
    } else if (!il_bsdf_is_delta(&b) && il_light_sample_at(s, surf.p, u_select, u_light, &ls) &&
        il_sides_agree(&surf, wo, ls.wi)) {
        float w = 1.0f, bsdf_pdf = 0.0f;
        il_vec3 f = il_bsdf_eval(&b, wo, ls.wi, &bsdf_pdf);
        if (!ls.delta)
            w = mis_weight(strategy, IL_PT_NEE_ONLY, ls.pdf, bsdf_pdf);
        float cos_i = fabsf(v3_dot(ls.wi, b.frame.n));
        if (w > 0.0f && cos_i > 0.0f && !v3_is_zero(f)) {
            if (isinf(ls.dist)) {
                st->shadow_ray = (il_ray){.org = il_offset_origin(tr, surf.p, surf.ng, ls.wi),
                                          .tmin = 0.0f, .dir = ls.wi, .tmax = INFINITY};
            } else {
                st->shadow_ray = il_shadow_ray(tr, surf.p, surf.ng, ls.p, ls.n);
            }
            st->shadow = true;
            st->rays++;
            st->shadow_L = v3_scale(v3_mul(st->beta, v3_mul(f, ls.radiance)), cos_i * w / ls.pdf);
        }
    }

    /* BSDF sampling continues the path. */
    il_vec3 beta;
    il_ray next;
    float pdf;
    bool delta = false;
    if (next_done) {
        if (!made->next_ok)
            return false;
        beta = made->next_beta;
        pdf = made->next_pdf;
        next = made->next_ray;
    } else {
        il_bsdf_sample bs;
        if (!il_bsdf_sample_dir_cos(&b, wo, u_lobe, u_bsdf, drawn ? &drawn->cos_dir : NULL, &bs) ||
            !il_sides_agree(&surf, wo, bs.wi))
            return false;
        beta = v3_mul(st->beta, bs.weight);
        pdf = bs.pdf;
        delta = bs.delta;
        next = (il_ray){.org = il_offset_origin(tr, surf.p, surf.ng, bs.wi), .tmin = 0.0f,
                        .dir = bs.wi, .tmax = INFINITY};
    }
    if (v3_is_zero(beta) || !v3_is_finite(beta))
        return false;
    st->specular = delta;
    st->camera_chain = st->camera_chain && delta;
    st->prev_pdf = pdf;
    st->prev_p = surf.p;
    st->ray = next;

    /* Russian roulette after the third vertex (pbrt-v4 13.4.4): survive
     * with probability q = min(max component of the throughput, 0.95) and
     * divide by q, which keeps the estimate unbiased. */
    if (depth >= 3) {
        float q = il_minf(v3_max_comp(beta), 0.95f);
        float u_rr = drawn && drawn->roulette ? drawn->u[3].x : il_sampler_1d(smp);
        if (!(u_rr < q)) {
            st->beta = beta;
            return false;
        }
        beta = v3_scale(beta, 1.0f / q);
    }
    st->beta = beta;
    st->depth = depth + 1;
    st->rays++;                   /* the next ray */
    return true;
}

/* Traces st->ray and the rays after it until the path ends. */
static void pt_continue(const il_scene *s, il_pt_state *st, il_sampler *smp, uint32_t max_depth,
                        il_pt_strategy strategy)
{
    const il_tracer *tr = s->tracer;
    for (;;) {
        il_hit hit;
        bool found = il_trace_closest(tr, &st->ray, &hit);
        bool more = il_pt_step(s, st, found ? &hit : NULL, smp, max_depth, strategy);
        if (st->shadow)
            il_pt_shadow_result(st, il_trace_visibility(tr, &st->shadow_ray));
        if (!more)
            break;
    }
}

il_vec3 il_pt_radiance(const il_scene *s, il_vec3 org, il_vec3 dir, il_sampler *smp,
                       uint32_t max_depth, il_pt_strategy strategy, uint64_t *rays)
{
    il_pt_state st;
    il_pt_begin(&st, org, dir);
    pt_continue(s, &st, smp, max_depth, strategy);
    *rays += st.rays;
    return st.L;
}

il_vec3 il_pt_radiance_scattered(const il_scene *s, const il_hit *hit, il_vec3 org, il_vec3 dir,
                                 il_sampler *smp, uint32_t max_depth, uint64_t *rays)
{
    il_surface surf;
    il_scene_surface(s, hit->mesh, hit->prim, hit->b1, hit->b2, &surf);
    il_pt_state st;
    il_pt_begin(&st, org, dir);
    st.rays = 0;                  /* the caller traced the first ray */
    /* The step adds the emission first, at weight 1 (st.specular): starting
     * from its negative leaves exactly zero of it. */
    if (!v3_is_zero(surf.material->emission))
        st.L = v3_neg(il_emitted_radiance(surf.material, surf.ng, v3_neg(dir)));
    bool more = il_pt_step_at(s, &st, hit, &surf, NULL, smp, max_depth, IL_PT_MIS);
    if (st.shadow)
        il_pt_shadow_result(&st, il_trace_visibility(s->tracer, &st.shadow_ray));
    if (more)
        pt_continue(s, &st, smp, max_depth, IL_PT_MIS);
    *rays += st.rays;
    return st.L;
}

/* A white Lambertian surface (albedo 1) reflects L = E / pi whatever the
 * direction it is seen from (Lambert's law, E = integral of L_i cos over the
 * hemisphere, f = 1/pi), so the path tracer's estimate of the radiance of
 * such a surface at p, times pi, estimates the irradiance there.  The
 * surface is not in the scene: nothing hits it, it blocks nothing. */
void il_pt_sensor_begin(il_pt_state *st, il_vec3 p, il_vec3 n, il_surface *surf, il_hit *hit)
{
    static const il_material white = {.type = IL_MATERIAL_DIFFUSE, .diffuse = {1.0f, 1.0f, 1.0f}};
    /* mesh 0, not IL_HIT_NONE: a hit to the wavefront; the step reads the
     * mesh only at an emitter, which this is not. */
    *surf = (il_surface){.p = p, .ng = n, .ns = n, .material = &white};
    *hit = (il_hit){.ng = n};
    il_pt_begin(st, v3_add(p, n), v3_neg(n)); /* seen along its normal */
    st->rays = 0;                              /* no ray reached the sensor */
}

il_vec3 il_pt_sensor_irradiance(const il_scene *s, il_vec3 p, il_vec3 n, il_sampler *smp,
                                uint32_t max_depth, uint64_t *rays)
{
    il_pt_state st;
    il_surface surf;
    il_hit sensor;
    il_pt_sensor_begin(&st, p, n, &surf, &sensor);
    bool more = il_pt_step_at(s, &st, &sensor, &surf, NULL, smp, max_depth, IL_PT_MIS);
    if (st.shadow)
        il_pt_shadow_result(&st, il_trace_visibility(s->tracer, &st.shadow_ray));
    if (more)
        pt_continue(s, &st, smp, max_depth, IL_PT_MIS);
    *rays += st.rays;
    return v3_scale(st.L, IL_PI);
}
