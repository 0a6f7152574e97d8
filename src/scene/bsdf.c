/* BSDFs of the material model; see bsdf.h and docs/materials.md.
 *
 * Conventions (as pbrt-v4, chapter 9): wo points towards the viewer (the
 * camera side of the path), wi towards the light; both are unit vectors
 * pointing away from the surface.  f excludes the cosine factor.  Opaque
 * materials work in the shading frame, flipped to wo's side so they are
 * two-sided. */
#include "scene/bsdf.h"

#include "core/sampling.h"
#include "scene/pane.h"

/* Directions closer than this to the tangent plane count as grazing: no energy. */
#define IL_BSDF_EPS 1e-7f

static il_vec3 clamp_colour(il_vec3 c)
{
    return v3_max(c, v3s(0.0f));
}

void il_bsdf_init(il_bsdf *b, const il_scene *scene, const il_surface *s)
{
    const il_material *m = s->material;
    b->type = m->type;
    b->frame = il_frame_from_normal(s->ns);
    b->ng = s->ng;
    b->diffuse = clamp_colour(scene ? il_material_diffuse(scene, m, s->uv) : m->diffuse);
    b->specular = clamp_colour(m->specular);
    b->exponent = il_phong_exponent(m);
    b->ior = m->ior > 0.0f ? m->ior : 1.5f;
    b->pane_tau = m->pane_tau;
    b->diffuse_prob = 1.0f;

    if (b->type == IL_MATERIAL_PHONG) {
        /* Energy conservation of the modified Phong model needs kd + ks <= 1
         * per channel (Lafortune & Willems 1994, section 3).  Scale both down
         * together, keeping their ratio, when a channel exceeds it. */
        float peak = v3_max_comp(v3_add(b->diffuse, b->specular));
        if (peak > 1.0f) {
            b->diffuse = v3_scale(b->diffuse, 1.0f / peak);
            b->specular = v3_scale(b->specular, 1.0f / peak);
        }
        /* Lobe selection in proportion to the albedos' luminance. */
        float ld = il_luminance(b->diffuse), ls = il_luminance(b->specular);
        b->diffuse_prob = ld + ls > 0.0f ? ld / (ld + ls) : 1.0f;
    }
}

bool il_bsdf_is_delta(const il_bsdf *b)
{
    return IL_MATERIAL_IS_DELTA(b->type);
}

/* ------------------------------------------------------ opaque: diffuse, phong */

/* f and pdf of the opaque non-delta lobes in the (flipped) local frame, where
 * wo.z > 0 is already known. */
static il_vec3 opaque_eval_local(const il_bsdf *b, il_vec3 wo, il_vec3 wi, float *pdf)
{
    if (wi.z <= IL_BSDF_EPS) {
        *pdf = 0.0f;
        return v3s(0.0f);
    }
    il_vec3 f = v3_scale(b->diffuse, IL_INV_PI);
    float p = il_cosine_hemisphere_pdf(wi.z);
    if (b->type == IL_MATERIAL_PHONG) {
        /* Modified Phong, normalised (Lafortune & Willems 1994, eq. for f_r):
         * f = kd/pi + ks (n+2)/(2 pi) cos^n(alpha), alpha between wi and the
         * mirror direction of wo. */
        il_vec3 r = v3(-wo.x, -wo.y, wo.z);
        float cos_alpha = v3_dot(wi, r);
        float n = b->exponent;
        float lobe = 0.0f;
        if (cos_alpha > 0.0f)
            lobe = powf(il_minf(cos_alpha, 1.0f), n);
        f = v3_fma(f, b->specular, (n + 2.0f) * IL_INV_2PI * lobe);
        /* Mixture pdf of the two sampling strategies (one-sample MIS over
         * lobes, Veach 1997 section 9.2.4). */
        float pd = b->diffuse_prob;
        p = pd * p + (1.0f - pd) * (n + 1.0f) * IL_INV_2PI * lobe;
    }
    *pdf = p;
    return f;
}

/* wo in the local frame, z flipped onto wo's side (two-sided shading).
 * False when wo is grazing. */
static bool opaque_local(const il_bsdf *b, il_vec3 wo, il_vec3 *wo_l, bool *flip)
{
    il_vec3 l = il_frame_to_local(&b->frame, wo);
    *flip = l.z < 0.0f;
    if (*flip)
        l.z = -l.z;
    *wo_l = l;
    return l.z > IL_BSDF_EPS;
}

/* Reflection only: wi and wo must lie on the same side of the geometric
 * surface, or light would leak through it where shading normals bend. */
static bool same_geometric_side(const il_bsdf *b, il_vec3 wo, il_vec3 wi)
{
    return v3_dot(wo, b->ng) * v3_dot(wi, b->ng) > 0.0f;
}

/* ------------------------------------------------------------- dielectric */

/* Unpolarised Fresnel reflectance of a smooth dielectric boundary (pbrt-v4
 * section 9.3, FrDielectric); cos_i > 0 on the incident side, eta the
 * relative index n_t / n_i.  Returns 1 on total internal reflection and the
 * transmitted cosine in *cos_t otherwise. */
static float fresnel_dielectric(float cos_i, float eta, float *cos_t)
{
    float sin2_i = il_maxf(0.0f, 1.0f - cos_i * cos_i);
    float sin2_t = sin2_i / (eta * eta);           /* Snell's law */
    if (sin2_t >= 1.0f) {
        *cos_t = 0.0f;
        return 1.0f;
    }
    float ct = sqrtf(il_maxf(0.0f, 1.0f - sin2_t));
    float r_parl = (eta * cos_i - ct) / (eta * cos_i + ct);
    float r_perp = (cos_i - eta * ct) / (cos_i + eta * ct);
    *cos_t = ct;
    return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

static bool dielectric_sample(const il_bsdf *b, il_vec3 wo, float u_lobe, il_bsdf_sample *out)
{
    /* The side is decided by the geometric normal, which is trustworthy. */
    float cos_og = v3_dot(wo, b->ng);
    if (cos_og == 0.0f)
        return false;
    bool entering = cos_og > 0.0f;
    float eta = entering ? b->ior : 1.0f / b->ior;
    il_vec3 n = entering ? b->frame.n : v3_neg(b->frame.n);
    float cos_i = v3_dot(wo, n);
    if (cos_i <= IL_BSDF_EPS) {
        /* The shading normal faces away from wo: fall back to the geometric one. */
        n = entering ? b->ng : v3_neg(b->ng);
        cos_i = fabsf(cos_og);
    }
    float cos_t;
    float F = fresnel_dielectric(cos_i, eta, &cos_t);

    if (u_lobe < F) {
        /* Specular reflection, chosen with probability F: weight F/F * tint. */
        il_vec3 wi = v3_sub(v3_scale(n, 2.0f * cos_i), wo);
        if (v3_dot(wi, b->ng) * cos_og <= 0.0f)
            return false;
        out->wi = wi;
        out->pdf = F;
        out->f = v3_scale(b->specular, F / cos_i);
        out->weight = b->specular;
    } else {
        /* Refraction (pbrt-v4 9.3, Refract): wt = -wo/eta + (cos_i/eta - cos_t) n. */
        il_vec3 wi = v3_fma(v3_scale(wo, -1.0f / eta), n, cos_i / eta - cos_t);
        wi = v3_normalize(wi);
        if (v3_dot(wi, b->ng) * cos_og >= 0.0f)
            return false;
        /* Radiance is compressed into a smaller solid angle when it enters a
         * denser medium: L scales by 1/eta^2 (pbrt-v4 9.5.2, non-symmetric
         * scattering due to refraction; TransportMode::Radiance). */
        float scale = 1.0f / (eta * eta);
        out->wi = wi;
        out->pdf = 1.0f - F;
        out->f = v3_scale(b->specular, (1.0f - F) * scale / il_maxf(cos_t, IL_BSDF_EPS));
        out->weight = v3_scale(b->specular, scale);
    }
    out->delta = true;
    return !v3_is_zero(out->weight);
}

/* -------------------------------------------------------------- thin pane */

/* A ray reaches a pane's surface only when the ray caster did not let it
 * through, which it does with the pane's transmittance T (trace.c's pane
 * filter): light passes a pane on a straight line, so every method sees it
 * pass without a vertex of its own, and a light sample's shadow ray passes
 * it with the same probability.  What arrives here is reflected about the
 * geometric normal with weight R / (1 - T), so that R of the light is
 * reflected in all (R + T = 1 for a pane without absorption: weight 1). */
static bool pane_sample(const il_bsdf *b, il_vec3 wo, il_bsdf_sample *out)
{
    float cos_og = v3_dot(wo, b->ng);
    if (cos_og == 0.0f)
        return false;
    il_vec3 n = cos_og > 0.0f ? b->ng : v3_neg(b->ng);
    float cos_i = fabsf(cos_og), R, T;
    il_pane_optics(b->ior, b->pane_tau, cos_i, &R, &T);
    if (!(T < 1.0f) || !(R > 0.0f))
        return false;
    float w = il_minf(R / (1.0f - T), 1.0f);
    out->wi = v3_sub(v3_scale(n, 2.0f * cos_i), wo);
    out->pdf = 1.0f;
    out->delta = true;
    out->f = v3s(w / cos_i);
    out->weight = v3s(w);
    return true;
}

/* ------------------------------------------------------------------ public */

il_vec3 il_bsdf_eval(const il_bsdf *b, il_vec3 wo, il_vec3 wi, float *pdf)
{
    float p = 0.0f;
    il_vec3 f = v3s(0.0f);
    if (!il_bsdf_is_delta(b) && same_geometric_side(b, wo, wi)) {
        il_vec3 wo_l, wi_l;
        bool flip;
        if (opaque_local(b, wo, &wo_l, &flip)) {
            wi_l = il_frame_to_local(&b->frame, wi);
            if (flip)
                wi_l.z = -wi_l.z;
            f = opaque_eval_local(b, wo_l, wi_l, &p);
        }
    }
    if (pdf)
        *pdf = p;
    return f;
}

bool il_bsdf_sample_dir(const il_bsdf *b, il_vec3 wo, float u_lobe, il_vec2 u, il_bsdf_sample *out)
{
    return il_bsdf_sample_dir_cos(b, wo, u_lobe, u, NULL, out);
}

bool il_bsdf_sample_dir_cos(const il_bsdf *b, il_vec3 wo, float u_lobe, il_vec2 u,
                            const il_vec3 *cos_dir, il_bsdf_sample *out)
{
    out->delta = false;
    out->pdf = 0.0f;
    out->f = out->weight = v3s(0.0f);
    out->wi = v3s(0.0f);

    if (b->type == IL_MATERIAL_DIELECTRIC)
        return dielectric_sample(b, wo, u_lobe, out);
    if (b->type == IL_MATERIAL_THIN_GLASS)
        return pane_sample(b, wo, out);

    il_vec3 wo_l;
    bool flip;
    if (!opaque_local(b, wo, &wo_l, &flip))
        return false;

    if (b->type == IL_MATERIAL_MIRROR) {
        /* Perfect reflection about the shading normal; the delta's weight is
         * the tint (a perfect conductor with Fresnel factor 1). */
        il_vec3 wi_l = v3(-wo_l.x, -wo_l.y, wo_l.z);
        il_vec3 wi = il_frame_to_world(&b->frame, v3(wi_l.x, wi_l.y, flip ? -wi_l.z : wi_l.z));
        if (!same_geometric_side(b, wo, wi))
            return false;
        out->wi = wi;
        out->pdf = 1.0f;
        out->delta = true;
        out->f = v3_scale(b->specular, 1.0f / wi_l.z);
        out->weight = b->specular;
        return !v3_is_zero(out->weight);
    }

    il_vec3 wi_l;
    if (b->type == IL_MATERIAL_PHONG && u_lobe >= b->diffuse_prob) {
        /* Sample the Phong lobe around the mirror direction. */
        il_vec3 r = v3(-wo_l.x, -wo_l.y, wo_l.z);
        il_frame rf = il_frame_from_normal(r);
        wi_l = il_frame_to_world(&rf, il_sample_phong_lobe(u, b->exponent));
    } else {
        wi_l = cos_dir ? *cos_dir : il_sample_cosine_hemisphere(u);
    }
    if (wi_l.z <= IL_BSDF_EPS)
        return false;   /* the lobe dipped below the horizon: no energy */

    float pdf;
    il_vec3 f = opaque_eval_local(b, wo_l, wi_l, &pdf);
    if (!(pdf > 0.0f))
        return false;
    il_vec3 wi = il_frame_to_world(&b->frame, v3(wi_l.x, wi_l.y, flip ? -wi_l.z : wi_l.z));
    if (!same_geometric_side(b, wo, wi))
        return false;
    out->wi = wi;
    out->f = f;
    out->pdf = pdf;
    out->weight = v3_scale(f, wi_l.z / pdf);
    return !v3_is_zero(out->weight);
}
