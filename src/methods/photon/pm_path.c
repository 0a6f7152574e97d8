/* Camera and gather paths through mirrors and glass to the first surface
 * whose light the photon maps describe. */
#include <math.h>

#include "methods/photon/pm.h"
#include "scene/lights.h"
#include "trace/trace.h"

bool il_pm_trace_to_diffuse(const il_scene *scene, il_ray ray, il_sampler *smp, uint32_t max_depth,
                            il_vec3 *emitted, il_pm_vertex *out, uint64_t *rays)
{
    const il_tracer *tr = scene->tracer;
    il_vec3 beta = v3(1.0f, 1.0f, 1.0f);
    for (uint32_t depth = 0;; depth++) {
        il_hit hit;
        (*rays)++;
        if (!il_trace_closest(tr, &ray, &hit)) {
            if (emitted)
                *emitted = v3_add(*emitted, v3_mul(beta, il_background_radiance(scene, ray.dir)));
            return false;
        }
        il_pm_vertex *v = out;
        il_scene_surface(scene, hit.mesh, hit.prim, hit.b1, hit.b2, &v->s);
        v->wo = v3_normalize(v3_neg(ray.dir));
        if (emitted && !v3_is_zero(v->s.material->emission))
            *emitted = v3_add(*emitted,
                              v3_mul(beta, il_emitted_radiance(v->s.material, v->s.ng, v->wo)));
        il_bsdf_init(&v->bsdf, scene, &v->s);
        if (!il_bsdf_is_delta(&v->bsdf)) {
            v->n = v3_dot(v->s.ng, v->wo) < 0.0f ? v3_neg(v->s.ng) : v->s.ng;
            v->beta = beta;
            v->depth = depth;
            return true;
        }
        if (depth >= max_depth)
            return false;
        float u_lobe = il_sampler_1d(smp);
        il_vec2 u = il_sampler_2d(smp);
        il_bsdf_sample bs;
        if (!il_bsdf_sample_dir(&v->bsdf, v->wo, u_lobe, u, &bs) || !il_sides_agree(&v->s, v->wo, bs.wi))
            return false;
        beta = v3_mul(beta, bs.weight);
        if (v3_is_zero(beta) || !v3_is_finite(beta))
            return false;
        ray = (il_ray){.org = il_offset_origin(tr, v->s.p, v->s.ng, bs.wi), .tmin = 0.0f,
                       .dir = bs.wi, .tmax = INFINITY};
    }
}
