/* Emitting a photon (or a Linespace injection path): a light chosen by
 * power, then a ray and the power it carries.  Dividing by the light's
 * selection probability makes every light's paths carry its whole power
 * however few of them it gets, so lights mix by power.  The photon's power is Le cos / (pmf pdf_A pdf_w), the estimator
 * of the light's emitted power (pbrt-v3 16.2.2, "Photon shooting" in SPPM,
 * and pbrt-v4 12.* Light::SampleLe; Jensen 2001, 5.1.1).  Every kind is
 * sampled so that this weight matches what lights.c lets the path tracer
 * receive from the same light, and so that it is the same for every photon
 * of a light (constant photon power keeps density estimates smooth). */
#include "methods/light_emit.h"

#include <math.h>
#include <string.h>

#include "core/sampling.h"
#include "scene/lights.h"
#include "methods/portal_light.h"
#include "scene/portal.h"
#include "trace/trace.h"

/* The light whose CDF interval holds u (the same choice as lights.c's
 * selection by power): binary search of scene->light_cdf. */
static uint32_t pick_light(const il_scene *s, float u)
{
    uint32_t lo = 0, hi = s->num_lights - 1;   /* cdf[lo] <= u, answer in [lo, hi] */
    while (lo < hi) {
        uint32_t mid = lo + (hi - lo + 1) / 2;
        if (s->light_cdf[mid] <= u)
            lo = mid;
        else
            hi = mid - 1;
    }
    return lo;
}

/* A point on the disk of radius r, centred at c and perpendicular to unit d. */
static il_vec3 disk_point(il_vec3 c, il_vec3 d, float r, il_vec2 u)
{
    il_frame f = il_frame_from_normal(d);
    il_vec2 q = il_sample_concentric_disk(u);
    return v3_fma(v3_fma(c, f.s, r * q.x), f.t, r * q.y);
}

/* Where a photon of a directional light, travelling along the unit dir,
 * starts: on the disk of radius R perpendicular to dir outside the
 * bounding sphere (centre c), drawn uniformly, density 1/(pi R^2) over its
 * plane.  In a scene with portals that dir enters by (scene/portal.h) the
 * line is drawn instead, with probability IL_PORTAL_SHARE, through a point
 * of those portals (il_portal_sample_point: density k / P over the same
 * plane, P their projected area, k the portal triangles the line enters
 * by), and the photon starts where that line meets the disk's plane.  The
 * sun through a window then reaches the room in most of its photons
 * instead of in the share of the disk the window covers (2.4 m^2 of a disk
 * of 57 m radius in scenes/window-room.json, less at a slant: 1 photon in
 * 4,800 for a sun 30 degrees up in front of it).  The two
 * are one mixture density (one-sample MIS with the balance heuristic,
 * Veach 1997, 9.2.4), so every line the disk holds stays sampled and the
 * estimate is unbiased whatever the portals cover.  (The environment
 * needs no such draw: the portals' light carries what it sends in,
 * methods/portal_light.c.)
 *
 * Only when `steer` (the light paths are split at the portals).  Returns
 * p_disk / p_mixture, the factor the photon's power (that of the disk
 * alone, E pi R^2) takes: exactly 1 without steering, 0 when the draw
 * failed. */
static float emit_origin(const il_scene *s, bool steer, il_vec3 dir, il_vec3 c, il_vec2 u_pos,
                         float u_choice, il_vec3 *org)
{
    float r = s->scene_radius;
    float projected = steer ? il_portal_projected_area(s, dir) : 0.0f;
    if (!(projected > 0.0f)) {
        *org = disk_point(c, dir, r, u_pos);
        return 1.0f;
    }
    bool in_disk = true;
    uint32_t k;
    if (u_choice < IL_PORTAL_SHARE) {
        il_vec3 x;
        if (!il_portal_sample_point(s, dir, projected, u_pos, &x))
            return 0.0f;
        *org = v3_fma(x, dir, v3_dot(v3_sub(c, x), dir));   /* onto the disk's plane */
        in_disk = v3_length2(v3_sub(*org, c)) <= r * r;     /* else the disk holds no such line */
        k = il_portal_lines_entering(s, x, dir);
        k = k > 0 ? k : 1;                                  /* x lies on one: rounding at an edge */
    } else {
        *org = disk_point(c, dir, r, u_pos);
        k = il_portal_lines_entering(s, *org, dir);
    }
    float disk_to_portal = IL_PI * r * r / projected;        /* p_portal per crossing / p_disk */
    return 1.0f / ((in_disk ? 1.0f - IL_PORTAL_SHARE : 0.0f) + IL_PORTAL_SHARE * (float)k * disk_to_portal);
}

/* A spot light's direction, drawn in proportion to its intensity profile
 * I(theta) = I cos^n(theta) for cos(theta) >= cos_max (lights.c; with n > 0
 * the profile ends at 90 degrees).  Inverting the CDF of cos^n(theta)
 * sin(theta) on [theta, theta_c]:
 *   cos(theta) = (1 - u (1 - cos_max^(n+1)))^(1/(n+1)),  phi = 2 pi u'.
 * The pdf is I(theta)/I / Z with Z = 2 pi (1 - cos_max^(n+1)) / (n+1), so
 * Le cos / pdf = I Z: every photon of the spot carries its whole power, the
 * Phi of lights.c's power_spot. */
static il_vec3 sample_spot(const il_light *l, il_vec2 u, float *z)
{
    float n = l->spot_exponent > 0.0f ? l->spot_exponent : 0.0f;
    float cm = l->cos_cutoff;
    if (n > 0.0f)
        cm = il_maxf(cm, 0.0f);
    cm = il_clampf(cm, -1.0f, 1.0f);
    float c;
    if (n > 0.0f) {
        float cmn = powf(cm, n + 1.0f);
        *z = 2.0f * IL_PI * (1.0f - cmn) / (n + 1.0f);
        c = powf(1.0f - u.x * (1.0f - cmn), 1.0f / (n + 1.0f));
    } else {
        *z = 2.0f * IL_PI * (1.0f - cm);
        c = 1.0f - u.x * (1.0f - cm);
    }
    c = il_clampf(c, cm, 1.0f);
    float s = sqrtf(il_maxf(0.0f, 1.0f - c * c));
    float phi = 2.0f * IL_PI * u.y;
    il_frame f = il_frame_from_normal(l->direction);
    return il_frame_to_world(&f, v3(s * cosf(phi), s * sinf(phi), c));
}

static bool emit(const il_scene *s, const float u[IL_LIGHT_EMIT_DIMS], float portal_share, bool inside,
                 il_pcg32 *rng, uint32_t max_depth, il_light_emission *out)
{
    memset(out, 0, sizeof *out);
    if (s->num_lights == 0 || !s->light_cdf || !s->light_pmf)
        return false;
    il_vec2 u_pos = v2(u[1], u[2]), u_dir = v2(u[3], u[4]);
    float u_light = u[0], lights_share = 1.0f;
    bool split = portal_share > 0.0f && portal_share < 1.0f && s->portal_light;
    out->split = split;
    /* Inside alone, the environment's chance in the table (its interval
     * [env_lo, env_lo + env_pmf)) goes to the other lights. */
    float env_pmf = 0.0f, env_lo = 0.0f;
    if (split && inside && s->environment_light != IL_NO_LIGHT) {
        env_pmf = s->light_pmf[s->environment_light];
        env_lo = s->light_cdf[s->environment_light];
    }
    if (split) {
        /* The environment alone: every path starts at the portals. */
        const float share = env_pmf >= 1.0f - 1e-6f ? 1.0f : portal_share;
        if (u_light < share)
            return il_portal_light_emit(s, u_light / share, u_pos, u_dir, rng, max_depth, share, out);
        u_light = il_clampf((u_light - share) / (1.0f - share), 0.0f, 0x1.fffffep-1f);
        lights_share = 1.0f - share;
    }
    if (env_pmf > 0.0f) {
        u_light *= 1.0f - env_pmf;
        if (u_light >= env_lo)
            u_light += env_pmf;
        u_light = il_minf(u_light, 0x1.fffffep-1f);
    }
    /* The lights by the scene's table: their power, or in a scene with
     * portals what they bring in by them (scene/lights.c). */
    uint32_t li = pick_light(s, u_light);
    if (env_pmf > 0.0f && li == s->environment_light)
        return false;   /* only by rounding at the interval's ends */
    float pmf = s->light_pmf[li];
    /* u_light within the light's interval, for the sun's steering (only a
     * split path steers through the portals). */
    float u_rest = split && pmf > 0.0f ? il_clampf((u_light - s->light_cdf[li]) / pmf, 0.0f, 0x1.fffffep-1f)
                                       : 0.0f;
    const il_light *l = &s->lights[li];
    if (!(pmf > 0.0f))
        return false;
    out->light = li;
    float inv_pmf = (1.0f - env_pmf) / (pmf * lights_share);

    switch (l->kind) {
    case IL_LIGHTK_POINT:
        /* Uniform over the sphere: pdf 1/(4 pi), power 4 pi I (pbrt-v4 12.1). */
        out->p = out->org = l->position;
        out->dir = il_sample_uniform_sphere(u_dir);
        out->power = v3_scale(l->intensity, 4.0f * IL_PI * inv_pmf);
        break;
    case IL_LIGHTK_SPOT: {
        float z;
        out->p = out->org = l->position;
        out->dir = sample_spot(l, u_dir, &z);
        out->power = v3_scale(l->intensity, z * inv_pmf);
        break;
    }
    case IL_LIGHTK_DIRECTIONAL: {
        /* A disk of the scene's bounding radius R facing the light, outside
         * the bounding sphere: pdf_A = 1/(pi R^2), power E pi R^2 (pbrt-v4
         * 12.4, DistantLight::SampleLe).  A light with a disc first draws
         * the direction over it (il_directional_sample): the disk then
         * faces that direction and the power is L Omega pi R^2, E pi R^2
         * times its scale. */
        float r = s->scene_radius, scale;
        il_vec3 dir = v3_neg(il_directional_sample(v3_neg(l->direction), l->cos_cutoff, u_dir, &scale));
        il_vec3 c = v3_fma(s->scene_center, dir, -r);
        float steered = emit_origin(s, split, dir, c, u_pos, u_rest, &out->org);
        out->p = out->org;
        out->dir = dir;
        out->power = v3_scale(l->intensity, IL_PI * r * r * scale * inv_pmf * steered);
        break;
    }
    case IL_LIGHTK_AREA: {
        /* A uniform point (pdf 1/A) and a cosine-weighted direction about
         * the front normal (pdf cos/pi): Le cos / (pdf_A pdf_w) = Le pi A.
         * A two-sided emitter picks its face with probability 1/2, which
         * doubles it (pbrt-v4 12.3, DiffuseAreaLight::SampleLe). */
        il_vec2 b = il_sample_triangle(u_pos);
        il_vec3 p, ng;
        il_scene_point(s, l->mesh, l->prim, b.x, b.y, &p, &ng);
        float scale = IL_PI * l->area * inv_pmf;
        il_vec3 nd = ng;
        if (l->two_sided) {
            if (u_dir.x < 0.5f) {
                nd = v3_neg(ng);
                u_dir.x = 2.0f * u_dir.x;
            } else {
                u_dir.x = 2.0f * u_dir.x - 1.0f;
            }
            u_dir.x = il_minf(u_dir.x, 0x1.fffffep-1f);
            scale *= 2.0f;
        }
        il_vec3 d_l = il_sample_cosine_hemisphere(u_dir);
        if (!(d_l.z > 0.0f))
            return false;   /* grazing: no power */
        il_frame f = il_frame_from_normal(nd);
        out->p = p;
        out->n = ng;
        out->dir = v3_normalize(il_frame_to_world(&f, d_l));
        out->org = il_offset_origin(s->tracer, p, ng, out->dir);
        out->power = v3_scale(l->radiance, scale);
        break;
    }
    case IL_LIGHTK_ENVIRONMENT: {
        /* Arriving from a direction w through a disk of radius R facing it
         * outside the bounding sphere (pdf 1/(pi R^2)): power
         * L(w) pi R^2 / pdf(w) (pbrt-v4 12.5.1-2, UniformInfiniteLight and
         * ImageInfiniteLight::SampleLe).  A constant sky: w uniform, pdf
         * 1/(4 pi), so every photon carries L 4 pi pi R^2, lights.c's
         * power_environment.  A map: w drawn from its importance tables
         * (il_environment_sample), so photons go where its light is and
         * carry nearly equal power. */
        float r = s->scene_radius;
        il_vec3 w, L;
        float scale;
        if (s->envmap) {
            float pdf;
            L = il_environment_sample(s, u_dir, &w, &pdf);
            if (!(pdf > 0.0f))
                return false;
            scale = IL_PI * r * r * inv_pmf / pdf;
        } else {
            w = il_sample_uniform_sphere(u_dir);
            L = il_environment_radiance(s, w);
            scale = 4.0f * IL_PI * IL_PI * r * r * inv_pmf;
        }
        il_vec3 c = v3_fma(s->scene_center, w, r);
        out->p = out->org = disk_point(c, w, r, u_pos);
        out->dir = v3_neg(w);
        out->power = v3_scale(L, scale);
        break;
    }
    default:
        return false;
    }
    return !v3_is_zero(out->power) && v3_is_finite(out->power);
}

/* The weight a photon (carrying power, importance transport) takes from a
 * sampled BSDF direction.  bsdf.c samples for radiance: a refraction scales
 * radiance by 1/eta^2 (pbrt-v4 9.5.2), which flux does not feel (pbrt-v4
 * TransportMode::Importance leaves the factor out), so it is undone. */
static il_vec3 flux_weight(const il_bsdf *b, il_vec3 wo, const il_bsdf_sample *bs)
{
    il_vec3 w = bs->weight;
    if (b->type == IL_MATERIAL_DIELECTRIC) {
        float co = v3_dot(wo, b->ng);
        if (co * v3_dot(bs->wi, b->ng) < 0.0f) {
            float eta = co > 0.0f ? b->ior : 1.0f / b->ior;
            w = v3_scale(w, eta * eta);
        }
    }
    return w;
}

bool il_light_emit(const il_scene *s, const float u[IL_LIGHT_EMIT_DIMS], float portal_share,
                   il_pcg32 *rng, uint32_t max_depth, il_light_emission *out)
{
    return emit(s, u, portal_share, false, rng, max_depth, out);
}

bool il_light_emit_inside(const il_scene *s, const float u[IL_LIGHT_EMIT_DIMS], float portal_share,
                          il_pcg32 *rng, uint32_t max_depth, il_light_emission *out)
{
    return emit(s, u, portal_share, true, rng, max_depth, out);
}

bool il_light_path_scatter(const il_tracer *tr, const il_surface *surf, const il_bsdf *b,
                           il_vec3 wo, il_pcg32 *rng, il_vec3 *power, il_ray *ray, bool *delta)
{
    float u_lobe = il_pcg32_float(rng);
    il_vec2 u_dir;
    u_dir.x = il_pcg32_float(rng);
    u_dir.y = il_pcg32_float(rng);
    float u_rr = il_pcg32_float(rng);

    il_bsdf_sample bs;
    if (!il_bsdf_sample_dir(b, wo, u_lobe, u_dir, &bs) || !il_sides_agree(surf, wo, bs.wi))
        return false;
    il_vec3 w = flux_weight(b, wo, &bs);
    /* Russian roulette on the sampled reflectance (Jensen 2001, 5.2.1;
     * pbrt-v3 16.2.2): survive with q = min(1, max_c w_c) and carry
     * power * w / q, so a grey surface keeps the photon's power as it is. */
    float q = il_minf(1.0f, v3_max_comp(w));
    if (!(u_rr < q))
        return false;
    *power = v3_mul(*power, v3_scale(w, 1.0f / q));
    if (v3_is_zero(*power) || !v3_is_finite(*power))
        return false;
    *delta = bs.delta;
    ray->org = il_offset_origin(tr, surf->p, surf->ng, bs.wi);
    ray->dir = bs.wi;
    ray->tmin = 0.0f;
    ray->tmax = INFINITY;
    return true;
}
