/* Light entering by the portals, as a light of its own for the light paths
 * of photon mapping, SPPM and Linespace's injection.
 *
 * Few photons of the environment enter a room by its window: the window
 * covers a small share of the disk they leave from (2.4 m^2 of a disk of
 * 57 m radius in scenes/window-room.json: 1/4,200 of its area, met at a
 * slant; 716 of 10^6 photons were stored), and fewer
 * still reach it after a bounce outside, off the ground.  A path tracer
 * finds the window from inside (scene/portal.h); light paths start
 * outside.  So in a scene with portals and light from outside (the
 * environment or a directional light), a share of the light paths
 * (il_portal_light_share) start at the portals instead: a uniform point x
 * of their area A, a direction d into their lit side, and the power of the
 * radiance arriving at x from outside,
 *
 *     Phi = L_in(x, -d) cos / (pdf_x pdf(d) share) = L_in cos A / (pdf(d) share),
 *
 * with L_in one sample of what the ray from x back out along -d brings:
 *   - the environment's radiance when the ray leaves the scene;
 *   - the radiance the surface it meets scatters towards x
 *     (il_pt_radiance_scattered, one path-traced sample).  That light has
 *     bounced: the path goes on as if it had bounced there (and as a
 *     caustic one when that surface is a mirror or glass).
 *
 * The paths of the lights themselves stop where they enter by a portal
 * (il_portal_light_stops), so that every way light comes in is counted
 * once, at its last entry:
 *   - every path after its first bounce (L_in's second term holds it);
 *   - the environment's paths from the start (L_in's first term);
 * what is left to the lights is their direct light entering by a portal,
 * which L_in leaves out: the sun through a window (its disc is not in
 * L_in's first term; light_emit.c draws its paths through the portals),
 * and the direct light of point, spot and area lights (L_in leaves out
 * what the surface met emits).  This is the window made a light source
 * (as Radiance's mkillum does), without its approximations: L_in is an
 * unbiased estimate and the split of the light paths is exact.
 *
 * The direction: half the draws cosine-distributed about the portal's
 * normal, half from the environment map's importance tables (so a sun in a
 * map is found; a draw that does not enter carries nothing), pdf(d) their
 * mixture (one-sample MIS with the balance heuristic, Veach 1997, 9.2.4);
 * without a map, cosine alone. */
#include "methods/portal_light.h"

#include <float.h>
#include <math.h>
#include <string.h>

#include "core/sampler.h"
#include "core/sampling.h"
#include "methods/pt/pt.h"
#include "scene/bsdf.h"
#include "scene/lights.h"
#include "scene/portal.h"

bool il_portal_light_emit(const il_scene *s, float u_choice, il_vec2 u_pos, il_vec2 u_dir,
                          il_pcg32 *rng, uint32_t max_depth, float share, il_light_emission *out)
{
    memset(out, 0, sizeof *out);
    out->light = IL_NO_LIGHT;
    out->split = true;
    out->portal = true;
    float area = il_portal_total_area(s);
    il_vec3 x, n;
    if (!(area > 0.0f) || !il_portal_point(s, area, u_pos, &x, &n))
        return false;

    bool env = s->has_environment && s->envmap;   /* a map's tables; a constant sky's are uniform */
    il_vec3 d;
    if (!env || u_choice < 0.5f) {
        il_frame f = il_frame_from_normal(n);
        d = il_frame_to_world(&f, il_sample_cosine_hemisphere(u_dir));
    } else {
        il_vec3 w;
        float pdf_env;
        il_environment_sample(s, u_dir, &w, &pdf_env);
        d = v3_neg(w);
    }
    float c = v3_dot(d, n);
    if (!(c >= IL_PORTAL_MIN_COS))
        return false;       /* grazing, or a draw of the map that does not enter */
    float pdf = c / IL_PI;
    if (env)
        pdf = 0.5f * pdf + 0.5f * il_environment_pdf(s, v3_neg(d));

    /* x lifted off the portal's plane to its outer side, as off a surface:
     * a pane in that plane is then in front of the path, not behind it. */
    const il_tracer *tr = s->tracer;
    il_vec3 o = il_offset_origin(tr, x, n, v3_neg(n));
    il_ray out_ray = {.org = o, .tmin = 0.0f, .dir = v3_neg(d), .tmax = INFINITY};
    il_hit hit;
    il_vec3 L;
    out->rays = 1;
    if (!il_trace_closest(tr, &out_ray, &hit)) {
        L = il_environment_radiance(s, out_ray.dir);
    } else {
        il_sampler smp;
        il_sampler_start(&smp, IL_SAMPLER_PCG, il_pcg32_next(rng), il_pcg32_next(rng), 0);
        L = il_pt_radiance_scattered(s, &hit, o, out_ray.dir, &smp, max_depth, &out->rays);
        il_surface surf;
        il_scene_surface(s, hit.mesh, hit.prim, hit.b1, hit.b2, &surf);
        il_bsdf b;
        il_bsdf_init(&b, s, &surf);
        out->scattered = true;
        out->caustic = il_bsdf_is_delta(&b);
    }
    out->p = out->org = o;
    out->dir = d;
    out->power = v3_scale(L, c * area / (pdf * share));
    return !v3_is_zero(out->power) && v3_is_finite(out->power);
}

float il_portal_light_share(const il_scene *s)
{
    float env = s->environment_light != IL_NO_LIGHT ? s->light_pmf[s->environment_light] : 0.0f;
    return il_clampf(env, 1.0f - IL_PORTAL_LIGHT_SHARE_MAX, IL_PORTAL_LIGHT_SHARE_MAX);
}

bool il_portal_light_wanted(const il_scene *s)
{
    return s->portal_light && il_portal_area_seen(s, s->camera.desc.position) > 0.0f;
}

/* How far past a portal's plane a path must end to have crossed it: a
 * path that ends on the plane (reflected by a pane in it) has not.  A few
 * times il_offset_origin's offset. */
static float crossing_margin(const il_scene *s, const il_ray *ray)
{
    float mag = il_maxf(fabsf(ray->org.x), il_maxf(fabsf(ray->org.y), fabsf(ray->org.z)));
    return 4.0f * (il_trace_epsilon(s->tracer) + mag * 4.0f * FLT_EPSILON);
}

bool il_portal_light_stops(const il_scene *s, const il_light_emission *e, uint32_t seg,
                           const il_ray *ray, float t_end, float *t_cross)
{
    if (!e->split)
        return false;
    if (seg == 0 && (e->portal || s->lights[e->light].kind != IL_LIGHTK_ENVIRONMENT))
        return false;
    return il_portal_entered(s, ray->org, ray->dir, t_end, crossing_margin(s, ray), t_cross);
}

bool il_portal_light_starts_inside(const il_scene *s, const il_light_emission *e, const il_ray *ray,
                                   float t_end)
{
    if (!e->split || e->portal)
        return true;
    il_light_kind kind = s->lights[e->light].kind;
    if (kind == IL_LIGHTK_ENVIRONMENT)
        return false;
    /* A lamp on a portal's lit side is inside, as the camera is
     * (il_portal_light_wanted); one elsewhere (a street lamp before the
     * window) and a sun are outside until they come in by a portal.  The
     * side is taken a hair along the path, so that a panel in the window
     * wall's plane, shining into the room, is inside. */
    if (kind != IL_LIGHTK_DIRECTIONAL &&
        il_portal_area_seen(s, v3_fma(ray->org, ray->dir, crossing_margin(s, ray))) > 0.0f)
        return true;
    return il_portal_light_enters(s, ray, t_end);
}

bool il_portal_light_leaves(const il_scene *s, const il_ray *ray, float t_end, float *t_cross)
{
    return il_portal_exited(s, ray->org, ray->dir, t_end, crossing_margin(s, ray), t_cross);
}

bool il_portal_light_enters(const il_scene *s, const il_ray *ray, float t_end)
{
    return il_portal_entered(s, ray->org, ray->dir, t_end, crossing_margin(s, ray), NULL);
}
