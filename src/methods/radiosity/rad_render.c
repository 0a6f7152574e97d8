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
 * - A path that leaves the scene takes the environment's radiance.  Point,
 *   spot and directional lights are invisible to camera rays (as in pt);
 *   their light is in the patches.
 *
 * The film loop is the path tracer's (pt.c): passes over 16x16 tiles, every
 * sample keyed by (seed, pixel, sample index), so the film is bit-identical
 * whatever the thread count. */
#include <omp.h>
#include <string.h>

#include "core/error.h"
#include "core/sampler.h"
#include "core/sampling.h"
#include "methods/pt/pt.h"
#include "methods/radiosity/rad.h"
#include "scene/bsdf.h"
#include "scene/camera.h"
#include "scene/lights.h"

#define IL_RR_TILE 16
/* Samples per pass: as in pt.c, small images get several samples per pixel
 * per pass so the per-pass cost stays negligible. */
#define IL_RR_PASS_SAMPLES 65536u
#define IL_RR_PASS_MAX_SPP 64u

typedef struct rr_job {
    const il_scene *scene;
    const il_rad_mesh *mesh;
    const il_vec3 *vrad;        /* per mesh vertex */
    il_film *film;
    il_camera cam;
    uint32_t width, height, tiles_x;
    uint32_t max_depth;
    uint64_t seed;
    il_sampler_type sampler;
    il_filter_type filter;
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
static il_vec3 rr_radiance(const rr_job *job, il_vec3 org, il_vec3 dir, il_sampler *smp,
                           uint64_t *rays)
{
    const il_scene *s = job->scene;
    const il_rad_mesh *mesh = job->mesh;
    const il_tracer *tr = mesh->tracer;
    il_vec3 L = v3s(0.0f), beta = v3s(1.0f);
    il_ray ray = {.org = org, .tmin = 0.0f, .dir = dir, .tmax = INFINITY};
    uint64_t nrays = 0;

    /* `depth` counts the scattering events before the current ray. */
    for (uint32_t depth = 0;; depth++) {
        il_hit hit;
        nrays++;
        if (!il_trace_closest(tr, &ray, &hit)) {
            L = v3_add(L, v3_mul(beta, il_environment_radiance(s, ray.dir)));
            break;
        }
        uint32_t t = hit.prim;
        uint32_t patch = mesh->tri_patch[t];
        il_vec3 wo = v3_neg(ray.dir);
        il_surface surf;
        il_bsdf b;
        il_vec3 wi, weight;

        if (patch != IL_RAD_NO_PATCH) {
            const il_rad_patch *pa = &mesh->patches[patch];
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
            /* Shading normals must not turn a reflection into a
             * transmission (Veach 1997, 5.3.2), as in pt_path.c. */
            float g = v3_dot(wo, surf.ng) * v3_dot(bs.wi, surf.ng);
            float n = v3_dot(wo, surf.ns) * v3_dot(bs.wi, surf.ns);
            if ((g > 0.0f) != (n > 0.0f) || g == 0.0f)
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

static void render_tile(const rr_job *job, uint32_t tile, uint32_t first, uint32_t count,
                        uint64_t *rays, uint64_t *bad)
{
    uint32_t x0 = (tile % job->tiles_x) * IL_RR_TILE, y0 = (tile / job->tiles_x) * IL_RR_TILE;
    uint32_t x1 = x0 + IL_RR_TILE < job->width ? x0 + IL_RR_TILE : job->width;
    uint32_t y1 = y0 + IL_RR_TILE < job->height ? y0 + IL_RR_TILE : job->height;
    for (uint32_t y = y0; y < y1; y++)
        for (uint32_t x = x0; x < x1; x++) {
            uint64_t pixel = (uint64_t)y * job->width + x;
            for (uint32_t i = first; i < first + count; i++) {
                il_sampler smp;
                il_sampler_start(&smp, job->sampler, job->seed, pixel, i);
                il_vec2 off = il_pt_filter_offset(job->filter, il_sampler_2d(&smp));
                il_vec3 dir = il_camera_ray_dir(&job->cam, (float)x + off.x, (float)y + off.y);
                il_vec3 L = rr_radiance(job, job->cam.position, dir, &smp, rays);
                if (!v3_is_finite(L)) {
                    (*bad)++;
                    continue;
                }
                il_film_add_sample(job->film, x, y, L, 1.0f);
            }
        }
}

/* stats: spp is set, rays and nonfinite_samples are added to (the solve may
 * have counted its own), radiosity.seconds_render is set; stats->seconds
 * (the whole method's time) is left to the caller. */
il_status il_rad_render_film(const il_scene *scene, const il_rad_mesh *mesh,
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

    rr_job job;
    memset(&job, 0, sizeof job);
    job.scene = scene;
    job.mesh = mesh;
    job.vrad = vertex_radiance;
    job.film = film;
    job.width = il_film_width(film);
    job.height = il_film_height(film);
    job.tiles_x = (job.width + IL_RR_TILE - 1) / IL_RR_TILE;
    job.max_depth = desc->max_depth ? desc->max_depth : 8;
    job.seed = desc->seed;
    job.sampler = desc->sampler;
    job.filter = desc->filter;
    il_camera_init(&job.cam, &scene->camera.desc, job.width, job.height);

    bool timed = desc->time_limit > 0.0;
    uint32_t spp = desc->spp ? desc->spp : (timed ? UINT32_MAX : 16u);
    int threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    uint64_t pixels = (uint64_t)job.width * job.height;
    uint32_t tiles = job.tiles_x * ((job.height + IL_RR_TILE - 1) / IL_RR_TILE);
    uint32_t per_pass = pixels ? (uint32_t)(IL_RR_PASS_SAMPLES / pixels) : 1u;
    per_pass = per_pass < 1 ? 1 : (per_pass > IL_RR_PASS_MAX_SPP ? IL_RR_PASS_MAX_SPP : per_pass);

    il_film_clear(film);
    double t0 = omp_get_wtime(), seconds = 0.0;
    uint64_t rays = 0, bad = 0;
    uint32_t done = 0;
    while (done < spp) {
        uint32_t count = spp - done < per_pass ? spp - done : per_pass;
        uint64_t pass_rays = 0, pass_bad = 0;
#pragma omp parallel for schedule(dynamic) num_threads(threads) reduction(+ : pass_rays, pass_bad)
        for (uint32_t t = 0; t < tiles; t++)
            render_tile(&job, t, done, count, &pass_rays, &pass_bad);
        done += count;
        rays += pass_rays;
        bad += pass_bad;
        seconds = omp_get_wtime() - t0;
        if (desc->progress) {
            il_render_progress p = {
                .passes_done = done,
                .passes_total = spp == UINT32_MAX ? 0 : spp,
                .seconds = seconds,
                .time_limit = desc->time_limit,
                .rays = rays,
                .film = film,
            };
            /* Stopping early is not an error: the film holds `done`
             * complete samples per pixel and stats.spp says so. */
            if (!desc->progress(&p, desc->progress_user))
                break;
        }
        if (timed && seconds >= desc->time_limit)
            break;
    }
    if (stats) {
        stats->spp = done;
        stats->rays += rays;
        stats->nonfinite_samples += bad;
        stats->radiosity.seconds_render = seconds;
    }
    return IL_OK;
}
