/* The light table; see lights.h.  Light sampling follows pbrt-v4 (Pharr,
 * Jakob, Humphreys 2023) chapter 12 "Light Sources"; power-proportional light
 * selection is its PowerLightSampler (12.6.2). */
#include "scene/lights.h"
#include "scene/portal.h"

#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/sampling.h"
#include "image/envmap.h"

/* Total emitted power of each kind, as luminance (pbrt-v4 Light::Phi). */

/* Point light: intensity I in every direction, Phi = 4 pi I (pbrt-v4 12.1). */
static float power_point(il_vec3 intensity) { return 4.0f * IL_PI * il_luminance(intensity); }

/* Spot light with I(theta) = I cos^n(theta) inside the cone theta < theta_c:
 * Phi = int_0^{2pi} int_0^{theta_c} I cos^n(theta) sin(theta) dtheta dphi
 *     = 2 pi I (1 - cos^{n+1}(theta_c)) / (n + 1). */
static float power_spot(il_vec3 intensity, float cos_cutoff, float n)
{
    /* With n > 0 the profile cos^n is taken as zero beyond 90 degrees, so a
     * wider cone adds nothing (and powf of a negative cosine is undefined). */
    if (n > 0.0f)
        cos_cutoff = fmaxf(cos_cutoff, 0.0f);
    return 2.0f * IL_PI * il_luminance(intensity) * (1.0f - powf(cos_cutoff, n + 1.0f)) / (n + 1.0f);
}

/* Directional light: irradiance E over a disk of the scene's radius R facing
 * it, Phi = pi R^2 E (pbrt-v4 12.4.1, DistantLight::Phi). */
static float power_directional(il_vec3 e, float radius)
{
    return IL_PI * radius * radius * il_luminance(e);
}

/* Lambertian emitter of radiance L and area A: Phi = pi L A per emitting face
 * (pbrt-v4 12.2, DiffuseAreaLight::Phi). */
static float power_area(il_vec3 radiance, float area, bool two_sided)
{
    return IL_PI * il_luminance(radiance) * area * (two_sided ? 2.0f : 1.0f);
}

/* Uniform environment of radiance L around a scene of radius R:
 * Phi = 4 pi * pi R^2 * L (pbrt-v4 12.5.1, UniformInfiniteLight::Phi).  A
 * map gives pi R^2 * int L dOmega = 4 pi * pi R^2 * mean(L) (pbrt-v4 12.5.2,
 * ImageInfiniteLight::Phi), so it is called with the map's mean radiance
 * over the sphere (envmap_sample.c). */
static float power_environment(il_vec3 radiance, float radius)
{
    return 4.0f * IL_PI * IL_PI * radius * radius * il_luminance(radiance);
}

/* The selection weights in a scene with portals (w holds the powers).
 * The environment's and the directional lights' power counts a disk the
 * size of the whole scene: a sky over the 80 m ground of
 * scenes/window-room.json outweighed a lamp in the room 14,000 to 1, and
 * the lamp's rare samples carried 14,000 times its light, as fireflies in
 * every method.  Portals mark an interior, and what those lights bring into
 * it is what enters by the portals: pi L A for a sky of mean radiance L
 * through portals of area A, E sum(A |cos|) for a sun of irradiance E.
 * Each keeps at least IL_OUTSIDE_MIN_SHARE of the total, so that points
 * outside (the ground seen through a window) and a sun in the portals'
 * plane are still sampled.  Any weights leave the estimates unbiased
 * (each sample divides by its own chance); these put the samples where
 * the light of an interior comes from. */
#define IL_OUTSIDE_MIN_SHARE 0.05f
static void interior_weights(const il_scene *s, float *w, uint32_t count)
{
    float area = il_portal_total_area(s), total = 0.0f;
    for (uint32_t i = 0; i < count; i++) {
        const il_light *l = &s->lights[i];
        if (l->kind == IL_LIGHTK_ENVIRONMENT) {
            w[i] = IL_PI * il_luminance(l->radiance) * area;
        } else if (l->kind == IL_LIGHTK_DIRECTIONAL) {
            float projected = 0.0f;
            for (uint32_t k = 0; k < s->num_portals; k++)
                projected += s->portals[k].area * fabsf(v3_dot(s->portals[k].n, l->direction));
            w[i] = il_luminance(l->intensity) * projected;
        }
        total += w[i];
    }
    if (!(total > 0.0f)) {      /* a lone sun in the portals' plane: by power */
        for (uint32_t i = 0; i < count; i++)
            w[i] = s->lights[i].power;
        return;
    }
    for (uint32_t i = 0; i < count; i++) {
        il_light_kind k = s->lights[i].kind;
        if ((k == IL_LIGHTK_ENVIRONMENT || k == IL_LIGHTK_DIRECTIONAL) && s->lights[i].power > 0.0f)
            w[i] = il_maxf(w[i], IL_OUTSIDE_MIN_SHARE * total);
    }
}

static void triangle_vertices(const il_scene *s, uint32_t mesh, uint32_t prim, il_vec3 v[3])
{
    const il_mesh *m = &s->meshes[mesh];
    const uint32_t *tri = m->indices + 3 * (size_t)prim;
    for (int k = 0; k < 3; k++)
        v[k] = m->positions[tri[k]];
}

void il_lights_free(il_scene *s)
{
    free(s->lights);
    free(s->light_cdf);
    free(s->light_pmf);
    free(s->light_recs);
    free(s->discs);
    if (s->triangle_light) {
        for (uint32_t i = 0; i < s->num_meshes; i++)
            free(s->triangle_light[i]);
        free(s->triangle_light);
    }
    s->lights = NULL;
    s->light_cdf = NULL;
    s->light_pmf = NULL;
    s->light_recs = NULL;
    s->triangle_light = NULL;
    s->discs = NULL;
    s->num_discs = 0;
    s->num_lights = 0;
    s->environment_light = IL_NO_LIGHT;
}

static il_status build_fail(il_scene *s, il_status st)
{
    il_lights_free(s);
    return st;
}

/* The record of light l with selection probability pmf (see il_light_rec). */
static il_light_rec light_rec(const il_scene *s, const il_light *l, float pmf)
{
    il_light_rec none = {.kind = IL_LREC_NONE};
    if (!(pmf > 0.0f))
        return none;
    switch (l->kind) {
    case IL_LIGHTK_AREA: {
        const il_mesh *m = &s->meshes[l->mesh];
        if (m->normals || !m->geom)
            return none;
        const il_tri_geom *g = &m->geom[l->prim];
        return (il_light_rec){.p0 = g->p0, .p1 = g->p1, .p2 = g->p2, .ng = g->ng, .radiance = l->radiance,
                              .area = l->area, .pmf = pmf, .two_sided = l->two_sided,
                              .kind = IL_LREC_TRIANGLE};
    }
    case IL_LIGHTK_POINT:
        return (il_light_rec){.p0 = l->position, .radiance = l->intensity, .pmf = pmf, .kind = IL_LREC_POINT};
    case IL_LIGHTK_SPOT:
        return (il_light_rec){.p0 = l->position, .p1 = l->direction, .radiance = l->intensity, .pmf = pmf,
                              .cos_cutoff = l->cos_cutoff, .spot_exponent = l->spot_exponent,
                              .kind = IL_LREC_SPOT};
    case IL_LIGHTK_DIRECTIONAL: /* il_light_sample_at's wi, computed once */
        return (il_light_rec){.p0 = v3_neg(l->direction), .radiance = l->intensity, .pmf = pmf,
                              .cos_cutoff = l->cos_cutoff, .kind = IL_LREC_DIRECTIONAL};
    case IL_LIGHTK_ENVIRONMENT:
        return (il_light_rec){.pmf = pmf, .kind = IL_LREC_ENVIRONMENT};
    default:
        return none;
    }
}

/* scene->light_recs; after the triangle records and the pmf. */
static il_status build_light_recs(il_scene *s, il_error *err)
{
    s->light_recs = il_malloc(s->num_lights * sizeof(il_light_rec), err);
    if (!s->light_recs)
        return build_fail(s, IL_ERR_MEMORY);
    for (uint32_t i = 0; i < s->num_lights; i++)
        s->light_recs[i] = light_rec(s, &s->lights[i], s->light_pmf[i]);
    return IL_OK;
}

/* scene->discs: the directional lights whose disc has a size.  A disc of
 * angular radius a and uniform radiance L gives a surface facing it
 * E = L pi sin^2 a (il_directional_sample), so L = E / (pi sin^2 a), with
 * sin^2 a = (1 - cos a)(1 + cos a) in double from the float cosine light
 * samples draw with, so that the disc the camera sees is theirs. */
static il_status build_discs(il_scene *s, il_error *err)
{
    uint32_t n = 0;
    for (uint32_t i = 0; i < s->num_lights; i++)
        n += s->lights[i].kind == IL_LIGHTK_DIRECTIONAL && s->lights[i].cos_cutoff < 1.0f;
    if (n == 0)
        return IL_OK;
    s->discs = il_malloc(n * sizeof(il_light_disc), err);
    if (!s->discs)
        return build_fail(s, IL_ERR_MEMORY);
    for (uint32_t i = 0; i < s->num_lights; i++) {
        const il_light *l = &s->lights[i];
        if (l->kind != IL_LIGHTK_DIRECTIONAL || !(l->cos_cutoff < 1.0f))
            continue;
        double c = l->cos_cutoff, sin2 = (1.0 - c) * (1.0 + c);
        s->discs[s->num_discs++] = (il_light_disc){
            .towards = v3_neg(l->direction), .sin2_radius = (float)sin2,
            .radiance = v3_scale(l->intensity, (float)(1.0 / (3.14159265358979323846 * sin2)))};
    }
    return IL_OK;
}

il_status il_lights_build(il_scene *s, il_error *err)
{
    il_lights_free(s);

    /* Count first: user lights, emissive triangles, the environment. */
    uint64_t n = s->num_user_lights + (s->has_environment ? 1u : 0u);
    for (uint32_t i = 0; i < s->num_meshes; i++)
        if (!v3_is_zero(s->materials[s->meshes[i].material].emission))
            n += s->meshes[i].num_triangles;
    if (n >= UINT32_MAX)
        return il_fail(err, IL_ERR_INVALID, "the scene has too many lights (%llu)",
                       (unsigned long long)n);

    s->triangle_light = il_calloc(s->num_meshes ? s->num_meshes : 1, sizeof(uint32_t *), err);
    s->lights = il_calloc(n ? n : 1, sizeof(il_light), err);
    if (!s->triangle_light || !s->lights)
        return build_fail(s, IL_ERR_MEMORY);

    uint32_t count = 0;
    for (uint32_t i = 0; i < s->num_user_lights; i++) {
        const il_light_desc *d = &s->user_lights[i];
        il_light l;
        memset(&l, 0, sizeof l);
        l.position = d->position;
        l.intensity = d->intensity;
        l.mesh = l.prim = IL_NO_LIGHT;
        /* Defaults of il_light_desc: zero direction is straight down, a zero
         * spot angle is 45 degrees. */
        l.direction = v3_is_zero(d->direction) ? v3(0.0f, -1.0f, 0.0f) : v3_normalize(d->direction);
        switch (d->type) {
        case IL_LIGHT_POINT:
            l.kind = IL_LIGHTK_POINT;
            l.power = power_point(d->intensity);
            break;
        case IL_LIGHT_SPOT: {
            float angle = d->spot_angle > 0.0f ? d->spot_angle : 45.0f;
            l.kind = IL_LIGHTK_SPOT;
            l.cos_cutoff = cosf(angle * IL_PI / 180.0f);
            l.spot_exponent = d->spot_exponent;
            l.power = power_spot(d->intensity, l.cos_cutoff, l.spot_exponent);
            break;
        }
        case IL_LIGHT_DIRECTIONAL:
        default:
            l.kind = IL_LIGHTK_DIRECTIONAL;
            l.cos_cutoff = d->diameter > 0.0f ? cosf(0.5f * d->diameter * IL_PI / 180.0f) : 1.0f;
            l.power = power_directional(d->intensity, s->scene_radius);
            break;
        }
        /* A light that emits nothing is left out: it could only waste samples. */
        if (l.power > 0.0f && isfinite(l.power))
            s->lights[count++] = l;
    }

    for (uint32_t i = 0; i < s->num_meshes; i++) {
        const il_mesh *m = &s->meshes[i];
        const il_material *mat = &s->materials[m->material];
        bool emissive = !v3_is_zero(mat->emission);
        s->triangle_light[i] = il_malloc((m->num_triangles ? m->num_triangles : 1) * sizeof(uint32_t), err);
        if (!s->triangle_light[i])
            return build_fail(s, IL_ERR_MEMORY);
        for (uint32_t t = 0; t < m->num_triangles; t++) {
            s->triangle_light[i][t] = IL_NO_LIGHT;
            if (!emissive)
                continue;
            il_vec3 v[3];
            triangle_vertices(s, i, t, v);
            float area = 0.5f * v3_length(v3_cross(v3_sub(v[1], v[0]), v3_sub(v[2], v[0])));
            if (!(area > 0.0f))
                continue;
            il_light l;
            memset(&l, 0, sizeof l);
            l.kind = IL_LIGHTK_AREA;
            l.mesh = i;
            l.prim = t;
            l.area = area;
            l.radiance = mat->emission;
            l.two_sided = mat->two_sided;
            l.power = power_area(mat->emission, area, mat->two_sided);
            s->triangle_light[i][t] = count;
            s->lights[count++] = l;
        }
    }

    if (s->has_environment) {
        il_light l;
        memset(&l, 0, sizeof l);
        l.kind = IL_LIGHTK_ENVIRONMENT;
        l.mesh = l.prim = IL_NO_LIGHT;
        /* A constant sky's radiance, or a map's mean (il_scene_set_environment). */
        l.radiance = s->envmap ? s->envmap->dist.mean : s->environment.radiance;
        l.power = power_environment(l.radiance, s->scene_radius);
        s->environment_light = count;
        s->lights[count++] = l;
    }

    if (count == 0)
        return build_fail(s, il_fail(err, IL_ERR_INVALID, "the scene has no light: add an emissive "
                                                          "material, a light, or an environment "
                                                          "(on the command line: --env MAP.hdr)"));
    s->num_lights = count;

    /* The selection distribution, proportional to power (in a scene with
     * portals, to what enters by them: interior_weights). */
    float *w = il_malloc(count * sizeof(float), err);
    if (!w)
        return build_fail(s, IL_ERR_MEMORY);
    for (uint32_t i = 0; i < count; i++)
        w[i] = s->lights[i].power;
    if (s->num_portals)
        interior_weights(s, w, count);
    il_distrib1d d;
    il_status st = il_distrib1d_init(&d, w, count, err);
    free(w);
    if (st != IL_OK)
        return build_fail(s, st);
    s->light_cdf = il_malloc(((size_t)count + 1) * sizeof(float), err);
    s->light_pmf = il_malloc(count * sizeof(float), err);
    if (!s->light_cdf || !s->light_pmf) {
        il_distrib1d_free(&d);
        return build_fail(s, IL_ERR_MEMORY);
    }
    memcpy(s->light_cdf, d.cdf, ((size_t)count + 1) * sizeof(float));
    for (uint32_t i = 0; i < count; i++)
        s->light_pmf[i] = il_distrib1d_pmf(&d, i);
    il_distrib1d_free(&d);
    s->portal_light = false;
    for (uint32_t i = 0; i < count && s->num_portals; i++)
        s->portal_light |= s->lights[i].kind == IL_LIGHTK_ENVIRONMENT ||
                           s->lights[i].kind == IL_LIGHTK_DIRECTIONAL;
    st = build_light_recs(s, err);
    return st == IL_OK ? build_discs(s, err) : st;
}

/* The light il_distrib1d_sample_discrete picks from the scene's selection
 * CDF for u (clamped into [0, 1) the same way). */
uint32_t il_light_select(const il_scene *s, float u)
{
    if (!(u >= 0.0f))
        u = 0.0f;
    if (u > 0x1.fffffep-1f)
        u = 0x1.fffffep-1f;
    return il_cdf_find(s->light_cdf, s->num_lights, u);
}

il_vec3 il_emitted_radiance(const il_material *m, il_vec3 ng, il_vec3 w)
{
    if (m->two_sided || v3_dot(ng, w) > 0.0f)
        return m->emission;
    return v3s(0.0f);
}

il_vec3 il_environment_radiance(const il_scene *s, il_vec3 dir)
{
    if (!s->has_environment)
        return v3s(0.0f);
    if (s->envmap)
        return il_envmap_eval(s->envmap, dir);
    return s->environment.radiance;
}

il_vec3 il_background_radiance(const il_scene *s, il_vec3 dir)
{
    il_vec3 L = il_environment_radiance(s, dir);
    for (uint32_t i = 0; i < s->num_discs; i++) {
        const il_light_disc *d = &s->discs[i];
        if (v3_dot(dir, d->towards) > 0.0f && v3_length2(v3_cross(dir, d->towards)) <= d->sin2_radius)
            L = v3_add(L, d->radiance);
    }
    return L;
}

/* Converts the area density 1/A of a uniform point on a triangle to solid
 * angle seen from the shading point: p_w = p_A * d^2 / |cos theta_l|
 * (pbrt-v4 4.2.3, equation 4.9). */
static float area_to_solid_angle(float area, float dist2, float cos_l)
{
    float c = fabsf(cos_l);
    return c > 0.0f && area > 0.0f ? dist2 / (area * c) : 0.0f;
}

/* Points the sample from p at the light point q: wi, dist, p; false when
 * the two coincide. */
static bool aim_at(il_light_sample *out, il_vec3 p, il_vec3 q, float *dist2)
{
    il_vec3 d = v3_sub(q, p);
    *dist2 = v3_length2(d);
    if (!(*dist2 > 0.0f))
        return false;
    out->dist = sqrtf(*dist2);
    out->wi = v3_scale(d, 1.0f / out->dist);
    out->p = q;
    return true;
}

il_vec3 il_directional_sample(il_vec3 towards, float cos_half, il_vec2 u, float *scale)
{
    *scale = 1.0f;
    if (!(cos_half < 1.0f))
        return towards;
    /* A disc of angular radius a and uniform radiance L gives a surface
     * facing it E = int L cos dw = L pi sin^2 a; drawn uniformly in its
     * cone (pdf 1 / (2 pi (1 - cos a))), L cos / pdf = E cos 2 / (1 + cos a). */
    *scale = 2.0f / (1.0f + cos_half);
    il_frame f = il_frame_from_normal(towards);
    return v3_normalize(il_frame_to_world(&f, il_sample_uniform_cone(u, cos_half)));
}

bool il_light_sample_at(const il_scene *s, il_vec3 p, float u_select, il_vec2 u, il_light_sample *out)
{
    memset(out, 0, sizeof *out);
    if (s->num_lights == 0)
        return false;
    uint32_t li = il_light_select(s, u_select);
    const il_light *l = &s->lights[li];
    float pmf = s->light_pmf[li];
    if (!(pmf > 0.0f))
        return false;
    out->light = li;

    switch (l->kind) {
    case IL_LIGHTK_POINT:
    case IL_LIGHTK_SPOT: {
        float dist2;
        if (!aim_at(out, p, l->position, &dist2))
            return false;
        out->pdf = pmf;
        out->delta = true;
        /* pbrt-v4 12.1: radiance arriving = I / d^2 (times the spot's profile). */
        float scale = 1.0f / dist2;
        if (l->kind == IL_LIGHTK_SPOT) {
            /* cos of the angle between the spot's axis and the direction to p. */
            float c = -v3_dot(l->direction, out->wi);
            if (c < l->cos_cutoff)
                return false;
            if (l->spot_exponent > 0.0f) {
                if (c <= 0.0f)
                    return false;
                scale *= powf(c, l->spot_exponent);
            }
        }
        out->radiance = v3_scale(l->intensity, scale);
        return true;
    }
    case IL_LIGHTK_DIRECTIONAL: {
        /* pbrt-v4 12.4: all light arrives from -direction, or from a
         * direction of its disc. */
        float scale;
        out->wi = il_directional_sample(v3_neg(l->direction), l->cos_cutoff, u, &scale);
        out->dist = INFINITY;
        out->radiance = v3_scale(l->intensity, scale);
        out->pdf = pmf;
        out->delta = true;
        return true;
    }
    case IL_LIGHTK_AREA: {
        /* Only the point and the normal of the surface: the light holds its
         * material's emission and sidedness (il_emitted_radiance's inputs). */
        il_vec2 b = il_sample_triangle(u);
        il_vec3 q, ng;
        il_scene_point(s, l->mesh, l->prim, b.x, b.y, &q, &ng);
        float dist2;
        if (!aim_at(out, p, q, &dist2))
            return false;
        out->n = ng;
        out->radiance = l->two_sided || v3_dot(ng, v3_neg(out->wi)) > 0.0f ? l->radiance : v3s(0.0f);
        out->pdf = pmf * area_to_solid_angle(l->area, dist2, v3_dot(ng, out->wi));
        return out->pdf > 0.0f && isfinite(out->pdf) && !v3_is_zero(out->radiance);
    }
    case IL_LIGHTK_ENVIRONMENT: {
        float pdf_dir;
        out->radiance = il_environment_sample_at(s, p, u, &out->wi, &pdf_dir);
        out->dist = INFINITY;
        out->pdf = pmf * pdf_dir;
        return out->pdf > 0.0f;
    }
    }
    return false;
}

float il_light_pdf_area(const il_scene *s, uint32_t light, il_vec3 p, il_vec3 p_light, il_vec3 n_light)
{
    if (light >= s->num_lights || s->lights[light].kind != IL_LIGHTK_AREA)
        return 0.0f;
    il_vec3 d = v3_sub(p_light, p);
    float dist2 = v3_length2(d);
    if (!(dist2 > 0.0f))
        return 0.0f;
    float cos_l = v3_dot(v3_normalize(n_light), d) / sqrtf(dist2);
    return s->light_pmf[light] * area_to_solid_angle(s->lights[light].area, dist2, cos_l);
}

/* The light table's density for the environment's density pdf_at (times its
 * selection; 0 when the table has no environment). */
static float environment_light_pdf(const il_scene *s, float pdf_at)
{
    return s->environment_light == IL_NO_LIGHT ? 0.0f : s->light_pmf[s->environment_light] * pdf_at;
}

float il_light_pdf_environment(const il_scene *s, il_vec3 p, il_vec3 dir)
{
    return environment_light_pdf(s, il_environment_pdf_at(s, p, dir));
}

il_vec3 il_environment_sample(const il_scene *s, il_vec2 u, il_vec3 *dir, float *pdf)
{
    /* A map: its importance-sampling tables (image/envmap_sample.c). */
    if (s->envmap && s->has_environment)
        return il_envmap_sample(s->envmap, u, dir, pdf);
    /* A constant sky: uniform over the sphere of directions (pbrt-v4 12.5.1). */
    *dir = il_sample_uniform_sphere(u);
    *pdf = s->has_environment ? IL_INV_4PI : 0.0f;
    return il_environment_radiance(s, *dir);
}

float il_environment_pdf(const il_scene *s, il_vec3 dir)
{
    if (!s->has_environment)
        return 0.0f;
    if (s->envmap)
        return il_envmap_pdf(s->envmap, dir);
    return IL_INV_4PI;
}

/* The radiance from dir and il_environment_pdf's density of it, sharing a
 * map's lookup (il_envmap_eval_pdf). */
static il_vec3 environment_eval(const il_scene *s, il_vec3 dir, float *pdf)
{
    if (!s->has_environment) {
        *pdf = 0.0f;
        return v3s(0.0f);
    }
    if (s->envmap)
        return il_envmap_eval_pdf(s->envmap, dir, pdf);
    *pdf = IL_INV_4PI;
    return s->environment.radiance;
}

/* The mixture of portal.h: a share IL_PORTAL_SHARE of the draws through the
 * portals lighting p, the rest from il_environment_sample (whose density of
 * dir is pdf_env), and the density of the mixture for either (one-sample
 * MIS, balance heuristic). */
static float mixture_pdf(const il_scene *s, il_vec3 p, float seen, il_vec3 dir, float pdf_env)
{
    return IL_PORTAL_SHARE * il_portal_pdf(s, p, seen, dir) + (1.0f - IL_PORTAL_SHARE) * pdf_env;
}

/* The area of the portals lighting p; 0 without portals or environment. */
static float portals_seen(const il_scene *s, il_vec3 p)
{
    return s->num_portals && s->has_environment ? il_portal_area_seen(s, p) : 0.0f;
}

/* il_environment_pdf_at's value, given il_environment_pdf's pdf_env. */
static float pdf_at_from(const il_scene *s, il_vec3 p, il_vec3 dir, float pdf_env)
{
    float seen = portals_seen(s, p);
    return seen > 0.0f ? mixture_pdf(s, p, seen, dir, pdf_env) : pdf_env;
}

il_vec3 il_environment_sample_at(const il_scene *s, il_vec3 p, il_vec2 u, il_vec3 *dir, float *pdf)
{
    float seen = portals_seen(s, p);
    if (!(seen > 0.0f))
        return il_environment_sample(s, u, dir, pdf);
    il_vec3 L;
    float pdf_env;
    if (u.x < IL_PORTAL_SHARE) {
        u.x = il_minf(u.x / IL_PORTAL_SHARE, 0x1.fffffep-1f);
        if (!il_portal_sample(s, p, seen, u, dir)) {
            *pdf = 0.0f;
            return v3s(0.0f);
        }
        L = environment_eval(s, *dir, &pdf_env);
    } else {
        u.x = il_minf((u.x - IL_PORTAL_SHARE) / (1.0f - IL_PORTAL_SHARE), 0x1.fffffep-1f);
        L = il_environment_sample(s, u, dir, &pdf_env);
        pdf_env = il_environment_pdf(s, *dir); /* the sampler's own, recomputed as pdf_at does */
    }
    *pdf = mixture_pdf(s, p, seen, *dir, pdf_env);
    return L;
}

float il_environment_pdf_at(const il_scene *s, il_vec3 p, il_vec3 dir)
{
    return pdf_at_from(s, p, dir, il_environment_pdf(s, dir));
}

il_vec3 il_environment_eval_at(const il_scene *s, il_vec3 p, il_vec3 dir, float *pdf)
{
    float pdf_env;
    il_vec3 L = environment_eval(s, dir, &pdf_env);
    *pdf = pdf_at_from(s, p, dir, pdf_env);
    return L;
}

il_vec3 il_environment_light_eval(const il_scene *s, il_vec3 p, il_vec3 dir, float *light_pdf)
{
    float pdf_at;
    il_vec3 L = il_environment_eval_at(s, p, dir, &pdf_at);
    *light_pdf = environment_light_pdf(s, pdf_at);
    return L;
}
