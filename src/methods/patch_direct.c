/* Direct light on a patch from the lights that are not patches: point, spot
 * and directional lights and the sky (shared by radiosity and hierarchical
 * radiosity; moved here from radiosity/rad_direct.c).
 *
 * For a Lambertian patch with reflectance rho under irradiance E the
 * reflected radiance is rho E / pi (Cohen & Wallace 1993, eq. 2.27 with
 * f_r = rho/pi); E is the mean over the patch by a 4 x 4 midpoint rule (delta
 * lights) and cosine rays with random numbers keyed by (seed, stream) (sky).
 *
 * Irradiance at p with unit normal n (conventions of src/scene/lights.c,
 * pbrt-v4 chapter 12):
 *   point/spot:   E = I * profile * cos(theta) / d^2, profile for a spot
 *                 cos^n(angle to its axis), zero beyond the cut-off;
 *   directional:  E = E_light * cos(theta), or for a light with a disc
 *                 the mean over directions drawn across it
 *                 (il_directional_sample), one per point;
 *   sky:          E = int L(w) cos dw = pi * mean of L over cosine-distributed
 *                 directions that escape the scene (pbrt-v4 A.5.3); with an
 *                 environment map or portals, cosine and environment
 *                 samples (il_environment_sample_at: through the portals
 *                 from a point they light) combined by MIS
 *                 (sky_map_irradiance). */
#include <math.h>

#include "core/rng.h"
#include "core/sampling.h"
#include "methods/patch_direct.h"
#include "scene/lights.h"
#include "trace/trace.h"

#define IL_DIRECT_GRID 4                                       /* points: 4 x 4 */
#define IL_DIRECT_POINTS (IL_DIRECT_GRID * IL_DIRECT_GRID)
#define IL_SKY_GRID 8                                          /* sky rays: 8 x 8 */
#define IL_SKY_RAYS (IL_SKY_GRID * IL_SKY_GRID)

/* The quadrature points of a patch: the midpoints of a 4 x 4 grid over its
 * parameter square with their weights (the midpoint rule, error O(h^2) for
 * smooth irradiance).  A quad uses its bilinear map P(u,v), each point
 * weighted by the area element |dP/du x dP/dv| (constant for a
 * parallelogram); a triangle the area-preserving square-to-triangle map
 * (equal weights). */
static void patch_points(const il_vec3 *corners, uint32_t num_corners,
                         il_vec3 points[IL_DIRECT_POINTS], float weights[IL_DIRECT_POINTS])
{
    il_vec3 c0 = corners[0], c1 = corners[1], c2 = corners[2];
    il_vec3 c3 = num_corners == 4 ? corners[3] : c0;
    float total = 0.0f;
    for (int k = 0; k < IL_DIRECT_POINTS; k++) {
        float u = ((float)(k % IL_DIRECT_GRID) + 0.5f) / IL_DIRECT_GRID;
        float v = ((float)(k / IL_DIRECT_GRID) + 0.5f) / IL_DIRECT_GRID;
        if (num_corners == 4) {
            il_vec3 a = v3_add(v3_scale(c0, (1 - u) * (1 - v)), v3_scale(c1, u * (1 - v)));
            il_vec3 b = v3_add(v3_scale(c2, u * v), v3_scale(c3, (1 - u) * v));
            points[k] = v3_add(a, b);
            il_vec3 du = v3_add(v3_scale(v3_sub(c1, c0), 1 - v), v3_scale(v3_sub(c2, c3), v));
            il_vec3 dv = v3_add(v3_scale(v3_sub(c3, c0), 1 - u), v3_scale(v3_sub(c2, c1), u));
            weights[k] = v3_length(v3_cross(du, dv));
        } else {
            il_vec2 bc = il_sample_triangle(v2(u, v));
            float b0 = 1.0f - bc.x - bc.y;
            points[k] = v3_add(v3_add(v3_scale(c0, b0), v3_scale(c1, bc.x)), v3_scale(c2, bc.y));
            weights[k] = 1.0f;
        }
        total += weights[k];
    }
    for (int k = 0; k < IL_DIRECT_POINTS; k++)
        weights[k] = total > 0.0f ? weights[k] / total : 1.0f / IL_DIRECT_POINTS;
}

/* Irradiance at p (unit normal n) from the scene's delta lights, with
 * shadows; u: the direction across a directional light's disc. */
static il_vec3 delta_irradiance(const il_scene *scene, il_vec3 p, il_vec3 n, il_vec2 u)
{
    il_vec3 e = v3s(0.0f);
    for (uint32_t l = 0; l < scene->num_lights; l++) {
        const il_light *light = &scene->lights[l];
        if (light->kind == IL_LIGHTK_POINT || light->kind == IL_LIGHTK_SPOT) {
            il_vec3 d = v3_sub(light->position, p);
            float dist2 = v3_length2(d);
            if (!(dist2 > 0.0f))
                continue;
            float dist = sqrtf(dist2);
            il_vec3 wi = v3_scale(d, 1.0f / dist);
            float cos_n = v3_dot(n, wi);
            if (cos_n <= 0.0f)
                continue;
            float scale = cos_n / dist2;
            if (light->kind == IL_LIGHTK_SPOT) {
                float c = -v3_dot(light->direction, wi); /* angle to the spot's axis */
                if (c < light->cos_cutoff)
                    continue;
                if (light->spot_exponent > 0.0f) {
                    if (c <= 0.0f)
                        continue;
                    scale *= powf(c, light->spot_exponent);
                }
            }
            il_ray ray = il_shadow_ray(scene->tracer, p, n, light->position, v3s(0.0f));
            e = v3_fma(e, light->intensity, scale * il_trace_visibility(scene->tracer, &ray));
        } else if (light->kind == IL_LIGHTK_DIRECTIONAL) {
            float scale;
            il_vec3 wi = il_directional_sample(v3_neg(light->direction), light->cos_cutoff, u, &scale);
            float cos_n = v3_dot(n, wi);
            if (cos_n <= 0.0f)
                continue;
            il_ray ray = {.org = il_offset_origin(scene->tracer, p, n, wi), .tmin = 0.0f, .dir = wi,
                          .tmax = INFINITY};
            e = v3_fma(e, light->intensity, cos_n * scale * il_trace_visibility(scene->tracer, &ray));
        }
    }
    return e;
}

static bool has_delta(const il_scene *scene)
{
    for (uint32_t l = 0; l < scene->num_lights; l++) {
        il_light_kind k = scene->lights[l].kind;
        if (k == IL_LIGHTK_POINT || k == IL_LIGHTK_SPOT || k == IL_LIGHTK_DIRECTIONAL)
            return true;
    }
    return false;
}

void il_patch_direct_kinds(const il_scene *scene, bool *delta, bool *sky)
{
    *delta = has_delta(scene);
    *sky = scene->has_environment;
}

/* Irradiance from an environment map or through portals (sums of L cos /
 * pdf, times the power-heuristic weight): half the rays cosine-distributed,
 * half drawn by il_environment_sample_at (the map's importance-sampling
 * tables, the portals), combined by multiple
 * importance sampling (Veach 1997, 9.2; equal counts, so the plain power
 * heuristic), so that a small bright sun is found as surely as a broad sky.
 * Jittered 8 x 4 strata for each technique, rays shared among the points. */
static il_vec3 sky_map_irradiance(const il_scene *scene, const il_vec3 *points, il_vec3 n, il_pcg32 *rng)
{
    il_frame f = il_frame_from_normal(n);
    il_vec3 sum = v3s(0.0f);
    const int half = IL_SKY_RAYS / 2;
    for (int r = 0; r < IL_SKY_RAYS; r++) {
        int k = r % half;
        float ux = ((float)(k % IL_SKY_GRID) + il_pcg32_float(rng)) / IL_SKY_GRID;
        float uy = ((float)(k / IL_SKY_GRID) + il_pcg32_float(rng)) / (IL_SKY_GRID / 2);
        uy = il_minf(uy, 0x1.fffffep-1f);
        il_vec3 dir, L;
        float pdf_cos, pdf_env, cos_n;
        il_vec3 p = points[(r * IL_DIRECT_POINTS) / IL_SKY_RAYS];
        if (r < half) {
            dir = il_frame_to_world(&f, il_sample_cosine_hemisphere(v2(ux, uy)));
            cos_n = v3_dot(dir, n);
            pdf_cos = il_cosine_hemisphere_pdf(cos_n);
            L = il_environment_eval_at(scene, p, dir, &pdf_env);
        } else {
            L = il_environment_sample_at(scene, p, v2(ux, uy), &dir, &pdf_env);
            cos_n = v3_dot(dir, n);
            pdf_cos = cos_n > 0.0f ? il_cosine_hemisphere_pdf(cos_n) : 0.0f;
        }
        float pdf = r < half ? pdf_cos : pdf_env;
        if (!(cos_n > 0.0f) || !(pdf > 0.0f) || v3_is_zero(L))
            continue;
        float w = r < half ? il_power_heuristic(pdf_cos, pdf_env) : il_power_heuristic(pdf_env, pdf_cos);
        if (!(w > 0.0f))
            continue; /* nothing to add (and a NaN would spread through a solve) */
        il_ray ray = {.org = il_offset_origin(scene->tracer, p, n, dir), .tmin = 0.0f, .dir = dir,
                      .tmax = INFINITY};
        sum = v3_fma(sum, L, w * cos_n / pdf * il_trace_visibility(scene->tracer, &ray));
    }
    return v3_scale(sum, 1.0f / (float)half);
}

il_vec3 il_patch_direct_irradiance(const il_scene *scene, const il_vec3 *corners,
                                   uint32_t num_corners, il_vec3 n, uint64_t seed,
                                   uint64_t stream, bool delta, bool sky)
{
    il_pcg32 rng = il_pcg32_seed(il_hash_combine(seed, 0x7261646469726563ull /* "raddirec" */),
                                 stream);
    il_vec3 points[IL_DIRECT_POINTS];
    float weights[IL_DIRECT_POINTS];
    patch_points(corners, num_corners, points, weights);
    il_vec3 e = v3s(0.0f);
    if (delta) {
        /* Directions across a directional light's disc: jittered 4 x 4
         * strata, the stratum of point k permuted (5k mod 16) so that a
         * row of points does not get a row of directions.  Its own stream:
         * the sky's numbers stay as they were. */
        il_pcg32 disc = il_pcg32_seed(il_hash_combine(seed, 0x73756e6469736373ull /* "sundiscs" */), stream);
        for (int k = 0; k < IL_DIRECT_POINTS; k++) {
            int st = (5 * k) % IL_DIRECT_POINTS;
            float ux = ((float)(st % IL_DIRECT_GRID) + il_pcg32_float(&disc)) / IL_DIRECT_GRID;
            float uy = ((float)(st / IL_DIRECT_GRID) + il_pcg32_float(&disc)) / IL_DIRECT_GRID;
            e = v3_fma(e, delta_irradiance(scene, points[k], n, v2(ux, uy)), weights[k]);
        }
    }
    if (sky && (scene->envmap || scene->num_portals)) {
        e = v3_add(e, sky_map_irradiance(scene, points, n, &rng));
    } else if (sky) {
        /* Cosine-distributed directions, jittered 8 x 8 strata, four per
         * point (the points' weights differ little from equal: ignored). */
        il_frame f = il_frame_from_normal(n);
        il_vec3 sum = v3s(0.0f);
        for (int r = 0; r < IL_SKY_RAYS; r++) {
            float ux = ((float)(r % IL_SKY_GRID) + il_pcg32_float(&rng)) / IL_SKY_GRID;
            float uy = ((float)(r / IL_SKY_GRID) + il_pcg32_float(&rng)) / IL_SKY_GRID;
            il_vec3 dir = il_frame_to_world(&f, il_sample_cosine_hemisphere(v2(ux, uy)));
            il_vec3 p = points[(r * IL_DIRECT_POINTS) / IL_SKY_RAYS];
            il_ray ray = {.org = il_offset_origin(scene->tracer, p, n, dir), .tmin = 0.0f,
                          .dir = dir, .tmax = INFINITY};
            float vis = il_trace_visibility(scene->tracer, &ray);
            if (vis > 0.0f)
                sum = v3_fma(sum, il_environment_radiance(scene, dir), vis);
        }
        e = v3_fma(e, sum, IL_PI / IL_SKY_RAYS);
    }
    return e;
}

