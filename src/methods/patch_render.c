/* The camera pass of radiosity (the second pass of a two-pass method,
 * Wallace, Cohen & Greenberg 1987, "A two-pass solution to the rendering
 * equation", SIGGRAPH '87): camera rays trace the meshed scene.
 *
 * - A diffuse patch seen from its front shows the radiance interpolated
 *   linearly from its triangle's vertices (Gouraud 1971; Cohen & Wallace
 *   1993, section 9.2).  Emission is already part of that radiance.
 *   Seen from its back a patch shows black: patches emit and reflect on
 *   their front only, so the solve holds no light for the back.
 * - A Phong patch adds its glossy lobe: one direction drawn from the Phong
 *   lobe continues the path, and whatever radiance is found there is
 *   reflected (the diffuse part is already in the patch's radiance).
 * - Mirror and glass triangles (no patch) continue the path by sampling
 *   their BSDF as the path tracer does; an emitting one shows its emission.
 * - A path that leaves the scene takes the environment's radiance, and
 *   after mirror and glass bounces only, a directional light's disc (the
 *   sun, il_background_radiance; as in pt).  Point and spot lights are
 *   invisible to camera rays; their light is in the patches.
 *
 * The film loop is the shared camera pass (methods/camera_pass.c), so the
 * film is bit-identical whatever the thread count. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "methods/camera_pass.h"
#include "methods/patch_mesh.h"
#include "scene/bsdf.h"
#include "scene/lights.h"

typedef struct rr_job {
    const il_scene *scene;
    const il_patch_mesh *mesh;
    const il_vec3 *vrad;        /* per mesh vertex */
    uint32_t max_depth;
} rr_job;

/* Barycentrics (b1, b2) of point p in triangle (a, b, c), p in its plane
 * (Ericson, "Real-Time Collision Detection", 2005, section 3.4), clamped to
 * the triangle against rounding. */
static il_vec2 barycentrics_of(il_vec3 p, il_vec3 a, il_vec3 b, il_vec3 c)
{
    il_vec3 e0 = v3_sub(b, a), e1 = v3_sub(c, a), e2 = v3_sub(p, a);
    float d00 = v3_dot(e0, e0), d01 = v3_dot(e0, e1), d11 = v3_dot(e1, e1);
    float d20 = v3_dot(e2, e0), d21 = v3_dot(e2, e1);
    float den = d00 * d11 - d01 * d01;
    if (!(den > 0.0f))
        return v2(0.0f, 0.0f);
    float b1 = il_clampf((d11 * d20 - d01 * d21) / den, 0.0f, 1.0f);
    float b2 = il_clampf((d00 * d21 - d01 * d20) / den, 0.0f, 1.0f - b1);
    return v2(b1, b2);
}

/* The glossy lobe of a Phong surface alone: wi drawn with density
 * (n+1)/(2 pi) cos^n(alpha) around the mirror direction of wo, and the
 * throughput f_s cos(theta_i) / pdf with f_s = ks (n+2)/(2 pi) cos^n(alpha)
 * (Lafortune & Willems 1994), i.e. ks (n+2)/(n+1) cos(theta_i).  Works in
 * the shading frame turned to wo's side, as bsdf.c does.  False when the
 * sample dips below the surface. */
static bool sample_glossy(const il_bsdf *b, il_vec3 wo, il_vec2 u, il_vec3 *wi, il_vec3 *weight)
{
    il_vec3 wo_l = il_frame_to_local(&b->frame, wo);
    bool flip = wo_l.z < 0.0f;
    if (flip)
        wo_l.z = -wo_l.z;
    if (!(wo_l.z > 0.0f) || v3_is_zero(b->specular))
        return false;
    il_vec3 r = v3(-wo_l.x, -wo_l.y, wo_l.z);
    il_frame rf = il_frame_from_normal(r);
    il_vec3 wi_l = il_frame_to_world(&rf, il_sample_phong_lobe(u, b->exponent));
    if (wi_l.z <= 1e-7f)
        return false;
    *wi = il_frame_to_world(&b->frame, v3(wi_l.x, wi_l.y, flip ? -wi_l.z : wi_l.z));
    /* Reflection only: wi must stay on wo's side of the geometric surface. */
    if (v3_dot(*wi, b->ng) * v3_dot(wo, b->ng) <= 0.0f)
        return false;
    *weight = v3_scale(b->specular, (b->exponent + 2.0f) / (b->exponent + 1.0f) * wi_l.z);
    return true;
}

/* The radiance arriving at org from direction -dir (dir unit) along one path. */
static il_vec3 rr_camera_radiance(const void *method, il_vec3 org, il_vec3 dir, il_sampler *smp,
                                  uint64_t *rays)
{
    const rr_job *job = method;
    const il_scene *s = job->scene;
    const il_patch_mesh *mesh = job->mesh;
    const il_tracer *tr = mesh->tracer;
    il_vec3 L = v3s(0.0f), beta = v3s(1.0f);
    il_ray ray = {.org = org, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    uint64_t nrays = 0;
    bool camera_chain = true; /* only mirror and glass bounces so far */

    /* `depth` counts the scattering events before the current ray. */
    for (uint32_t depth = 0;; depth++) {
        il_hit hit;
        nrays++;
        if (!il_trace_closest(tr, &ray, &hit)) {
            L = v3_add(L, v3_mul(beta, camera_chain ? il_background_radiance(s, ray.dir)
                                                    : il_environment_radiance(s, ray.dir)));
            break;
        }
        uint32_t t = hit.prim;
        uint32_t patch = mesh->tri_patch[t];
        il_vec3 wo = v3_neg(ray.dir);
        il_surface surf;
        il_bsdf b;
        il_vec3 wi, weight;

        if (patch != IL_NO_PATCH) {
            const il_patch *pa = &mesh->patches[patch];
            if (v3_dot(pa->normal, wo) <= 0.0f)
                break;  /* the back of a patch: black (see the top of the file) */
            const uint32_t *tri = mesh->tri_indices + 3 * (size_t)t;
            float b1 = hit.b1, b2 = hit.b2, b0 = 1.0f - b1 - b2;
            /* Gouraud: linear interpolation of the vertex radiance. */
            il_vec3 Lv = v3_add(v3_add(v3_scale(job->vrad[tri[0]], b0), v3_scale(job->vrad[tri[1]], b1)),
                                v3_scale(job->vrad[tri[2]], b2));
            L = v3_add(L, v3_mul(beta, Lv));

            uint32_t src_mesh = mesh->tri_src_mesh[t], src_prim = mesh->tri_src_prim[t];
            const il_mesh *sm = &s->meshes[src_mesh];
            if (s->materials[sm->material].type != IL_MATERIAL_PHONG || depth >= job->max_depth)
                break;
            /* The patch triangle lies inside scene triangle (src_mesh,
             * src_prim) with other barycentrics: find the hit point's own
             * there for the shading normal and uv. */
            const il_vec3 *P = mesh->positions;
            il_vec3 p = v3_add(v3_add(v3_scale(P[tri[0]], b0), v3_scale(P[tri[1]], b1)),
                               v3_scale(P[tri[2]], b2));
            const uint32_t *st = sm->indices + 3 * (size_t)src_prim;
            il_vec2 sb = barycentrics_of(p, sm->positions[st[0]], sm->positions[st[1]],
                                         sm->positions[st[2]]);
            il_scene_surface(s, src_mesh, src_prim, sb.x, sb.y, &surf);
            surf.p = p;
            il_bsdf_init(&b, s, &surf);
            /* Two pairs of numbers per vertex, always, as for mirror/glass:
             * a vertex's numbers never depend on the branch taken. */
            (void)il_sampler_2d(smp);
            il_vec2 u = il_sampler_2d(smp);
            if (!sample_glossy(&b, wo, u, &wi, &weight))
                break;
            /* Past a glossy bounce the sun's disc is left out: the lobe
             * would find so small a disc too rarely to be more than noise. */
            camera_chain = false;
        } else {
            /* Mirror or glass: same vertex order as the scene triangle, so
             * the hit's barycentrics are the scene triangle's. */
            il_scene_surface(s, mesh->tri_src_mesh[t], mesh->tri_src_prim[t], hit.b1, hit.b2, &surf);
            const il_material *m = surf.material;
            if (!v3_is_zero(m->emission))
                L = v3_add(L, v3_mul(beta, il_emitted_radiance(m, surf.ng, wo)));
            if (depth >= job->max_depth)
                break;
            il_bsdf_init(&b, s, &surf);
            il_vec2 u_choice = il_sampler_2d(smp);
            il_vec2 u = il_sampler_2d(smp);
            /* A triangle without patch that is not specular would need
             * light sampling the camera pass does not do: it stays black. */
            il_bsdf_sample bs;
            if (!il_bsdf_is_delta(&b) || !il_bsdf_sample_dir(&b, wo, u_choice.y, u, &bs))
                break;
            if (!il_sides_agree(&surf, wo, bs.wi))
                break;
            wi = bs.wi;
            weight = bs.weight;
        }
        beta = v3_mul(beta, weight);
        if (v3_is_zero(beta) || !v3_is_finite(beta))
            break;
        ray = (il_ray){.org = il_offset_origin(tr, surf.p, surf.ng, wi), .tmin = 0.0f, .dir = wi,
                       .tmax = INFINITY};
    }
    *rays += nrays;
    return L;
}

/* stats: spp is set, rays and nonfinite_samples are added to (the solve may
 * have counted its own); the method's own fields and stats->seconds are left
 * to the caller. */
il_status il_patch_render_film(const il_scene *scene, const il_patch_mesh *mesh,
                               const il_vec3 *vertex_radiance, il_film *film,
                               const il_render_desc *desc, il_render_stats *stats, il_error *err)
{
    if (!scene || !mesh || !vertex_radiance || !film || !desc)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity render: scene, mesh, vertex radiance, film and options are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "radiosity render: the scene is not committed (call il_scene_commit)");
    if (!mesh->tracer)
        return il_fail(err, IL_ERR_INVALID, "radiosity render: the mesh has no ray-casting structure");

    rr_job job = {.scene = scene, .mesh = mesh, .vrad = vertex_radiance,
                  .max_depth = desc->max_depth ? desc->max_depth : 8};
    il_camera_pass_result r;
    il_camera_pass(scene, film, desc, rr_camera_radiance, &job, &r);
    if (stats) {
        stats->spp = r.spp;
        stats->rays += r.rays;
        stats->nonfinite_samples += r.nonfinite_samples;
    }
    return IL_OK;
}

il_status il_patch_solve_and_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                                    il_patch_solve_fn solve, il_render_stats *stats,
                                    double *seconds_render, il_error *err)
{
    double t0 = omp_get_wtime();
    il_patch_mesh *mesh = NULL;
    il_vec3 *vr = NULL;
    il_status st = solve(scene, desc, &mesh, &vr, stats, err);
    if (st != IL_OK)
        return st;
    /* The camera pass sets spp and adds its rays to the solver's stats. */
    double t1 = omp_get_wtime();
    st = il_patch_render_film(scene, mesh, vr, film, desc, stats, err);
    *seconds_render = omp_get_wtime() - t1;
    stats->seconds = omp_get_wtime() - t0;
    il_patch_mesh_release(mesh);
    free(vr);
    return st;
}
