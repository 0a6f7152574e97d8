/* The BSDFs of the path kernel (kernel/kernel_path.h), shared by gcc and
 * nvcc: Lambertian, the normalised modified Phong model, the perfect mirror
 * and the smooth dielectric, evaluated, sampled and with the pdf of
 * scene/bsdf.c (the CPU's), in world space: the
 * CPU's local frame flipped onto wo's side is the shading normal ns turned
 * to wo, and the mirror direction (-wo.x, -wo.y, wo.z) of that frame is
 * 2 (wo . n) n - wo.  Directions are unit vectors pointing away from the
 * surface; f excludes the cosine. */
#ifndef IL_KERNEL_BSDF_H
#define IL_KERNEL_BSDF_H

#include "kernel/kernel_math.h"

#define ILK_PI 3.14159265358979323846f
#define ILK_INV_PI 0.31830988618379067154f
#define ILK_INV_2PI 0.15915494309189533577f
/* Directions closer than this to the tangent plane carry no energy (IL_BSDF_EPS). */
#define ILK_BSDF_EPS 1e-7f

/* ilk_material.type */
#define ILK_MATERIAL_DIFFUSE 0u
#define ILK_MATERIAL_PHONG 1u
#define ILK_MATERIAL_MIRROR 2u
#define ILK_MATERIAL_DIELECTRIC 3u

typedef struct ilk_material {
    ilk_vec3 diffuse;      /* albedo, clamped and (Phong) scaled as il_bsdf_init */
    uint32_t two_sided;    /* emits from both faces */
    ilk_vec3 emission;     /* radiance */
    uint32_t type;         /* ILK_MATERIAL_* */
    ilk_vec3 specular;     /* Phong: ks, scaled with kd as il_bsdf_init; mirror, glass: tint */
    float exponent;        /* Phong: n (32 when the material gives none) */
    float diffuse_prob;    /* Phong: probability of sampling the diffuse lobe */
    float ior;             /* glass: index of refraction (1.5 when none given) */
    uint32_t texture;      /* 0: none; else 1 + an index into the scene's textures: diffuse
                              is then the material's own colour and specular its clamped ks,
                              resolved per hit by ilk_material_at */
    float pad;
} ilk_material;

/* The BSDF at a surface point. */
typedef struct ilk_bsdf {
    const ilk_material *m;
    ilk_vec3 ng, ns;       /* unit geometric and shading normals */
} ilk_bsdf;

/* An orthonormal basis (s, t) around the unit vector n (Duff et al. 2017,
 * "Building an Orthonormal Basis, Revisited", JCGT 6(1)). */
IL_DEVICE_INLINE void ilk_basis(ilk_vec3 n, ilk_vec3 *s, ilk_vec3 *t)
{
    float sign = n.z >= 0.0f ? 1.0f : -1.0f;
    float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    *s = ilk_v3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    *t = ilk_v3(b, sign + n.y * n.y * a, -n.y);
}

/* The local direction (x, y, z) around n in world space. */
IL_DEVICE_INLINE ilk_vec3 ilk_from_local(ilk_vec3 n, float x, float y, float z)
{
    ilk_vec3 s, t;
    ilk_basis(n, &s, &t);
    return ilk_add(ilk_add(ilk_scale(s, x), ilk_scale(t, y)), ilk_scale(n, z));
}

/* Cosine-weighted direction around the unit normal n (Malley's method,
 * pbrt-v4 section A.5.3): density cos / pi. */
IL_DEVICE_INLINE ilk_vec3 ilk_cosine_dir(ilk_vec3 n, float u1, float u2)
{
    float r = sqrtf(u1), phi = 2.0f * ILK_PI * u2;
    return ilk_from_local(n, r * cosf(phi), r * sinf(phi), sqrtf(ilk_maxf(0.0f, 1.0f - u1)));
}

/* Phong lobe around the unit axis r, as core/sampling.c's
 * il_sample_phong_lobe: cos alpha = u1^(1/(n+1)), density
 * (n+1)/(2 pi) cos^n alpha. */
IL_DEVICE_INLINE ilk_vec3 ilk_phong_dir(ilk_vec3 r, float exponent, float u1, float u2)
{
    float c = powf(u1, 1.0f / (exponent + 1.0f));
    float s = sqrtf(ilk_maxf(0.0f, 1.0f - c * c)), phi = 2.0f * ILK_PI * u2;
    return ilk_from_local(r, s * cosf(phi), s * sinf(phi), c);
}

/* The shading normal turned to wo's side (the CPU's flipped local frame)
 * and cos theta_o; false when wo is grazing. */
IL_DEVICE_INLINE bool ilk_bsdf_side(const ilk_bsdf *b, ilk_vec3 wo, ilk_vec3 *n, float *cos_o)
{
    float c = ilk_dot(wo, b->ns);
    *n = c < 0.0f ? ilk_scale(b->ns, -1.0f) : b->ns;
    *cos_o = c < 0.0f ? -c : c;
    return *cos_o > ILK_BSDF_EPS;
}

/* f and pdf with n and cos_o from ilk_bsdf_side (scene/bsdf.c,
 * opaque_eval_local): kd/pi + ks (n+2)/(2 pi) cos^n alpha (Lafortune &
 * Willems 1994), the pdf the lobe mixture of ilk_bsdf_sample. */
IL_DEVICE_INLINE ilk_vec3 ilk_bsdf_eval_side(const ilk_bsdf *b, ilk_vec3 n, float cos_o, ilk_vec3 wo, ilk_vec3 wi,
                                             float *pdf)
{
    float cos_i = ilk_dot(wi, n);
    if (cos_i <= ILK_BSDF_EPS) {
        *pdf = 0.0f;
        return ilk_v3(0, 0, 0);
    }
    const ilk_material *m = b->m;
    ilk_vec3 f = ilk_scale(m->diffuse, ILK_INV_PI);
    float p = cos_i * ILK_INV_PI;
    if (m->type == ILK_MATERIAL_PHONG) {
        ilk_vec3 r = ilk_sub(ilk_scale(n, 2.0f * cos_o), wo);
        float cos_alpha = ilk_dot(wi, r), ex = m->exponent, lobe = 0.0f;
        if (cos_alpha > 0.0f)
            lobe = powf(ilk_minf(cos_alpha, 1.0f), ex);
        f = ilk_add(f, ilk_scale(m->specular, (ex + 2.0f) * ILK_INV_2PI * lobe));
        float pd = m->diffuse_prob;
        p = pd * p + (1.0f - pd) * (ex + 1.0f) * ILK_INV_2PI * lobe;
    }
    *pdf = p;
    return f;
}

/* f(wo, wi) and the pdf of ilk_bsdf_sample choosing wi (il_bsdf_eval):
 * zero for the delta BSDFs; reflection only, on the same side of the geometric surface. */
IL_DEVICE_INLINE ilk_vec3 ilk_bsdf_eval(const ilk_bsdf *b, ilk_vec3 wo, ilk_vec3 wi, float *pdf)
{
    ilk_vec3 n;
    float cos_o;
    *pdf = 0.0f;
    if (b->m->type == ILK_MATERIAL_MIRROR || b->m->type == ILK_MATERIAL_DIELECTRIC ||
        !(ilk_dot(wo, b->ng) * ilk_dot(wi, b->ng) > 0.0f) || !ilk_bsdf_side(b, wo, &n, &cos_o))
        return ilk_v3(0, 0, 0);
    return ilk_bsdf_eval_side(b, n, cos_o, wo, wi, pdf);
}

/* Mirror and glass: every lobe a delta, unreachable by light sampling. */
IL_DEVICE_INLINE bool ilk_bsdf_is_delta(const ilk_material *m)
{
    return m->type == ILK_MATERIAL_MIRROR || m->type == ILK_MATERIAL_DIELECTRIC;
}

/* Unpolarised Fresnel reflectance of a smooth dielectric boundary (pbrt-v4
 * section 9.3, FrDielectric), as scene/bsdf.c: cos_i > 0 on the incident
 * side, eta = n_t / n_i; 1 on total internal reflection, else the
 * transmitted cosine in *cos_t. */
IL_DEVICE_INLINE float ilk_fresnel_dielectric(float cos_i, float eta, float *cos_t)
{
    float sin2_i = ilk_maxf(0.0f, 1.0f - cos_i * cos_i);
    float sin2_t = sin2_i / (eta * eta);           /* Snell's law */
    if (sin2_t >= 1.0f) {
        *cos_t = 0.0f;
        return 1.0f;
    }
    float ct = sqrtf(ilk_maxf(0.0f, 1.0f - sin2_t));
    float r_parl = (eta * cos_i - ct) / (eta * cos_i + ct);
    float r_perp = (cos_i - eta * ct) / (cos_i + eta * ct);
    *cos_t = ct;
    return 0.5f * (r_parl * r_parl + r_perp * r_perp);
}

/* Smooth glass (scene/bsdf.c, dielectric_sample): reflection with
 * probability F (weight: the tint), else refraction (pbrt-v4 9.3, Refract;
 * weight tint / eta^2, radiance compressed into the denser medium, pbrt-v4
 * 9.5.2).  The side is decided by the geometric normal. */
IL_DEVICE_INLINE bool ilk_dielectric_sample(const ilk_bsdf *b, ilk_vec3 wo, float u_lobe, ilk_vec3 *wi,
                                            ilk_vec3 *weight)
{
    float cos_og = ilk_dot(wo, b->ng);
    if (cos_og == 0.0f)
        return false;
    bool entering = cos_og > 0.0f;
    float eta = entering ? b->m->ior : 1.0f / b->m->ior;
    ilk_vec3 n = entering ? b->ns : ilk_scale(b->ns, -1.0f);
    float cos_i = ilk_dot(wo, n);
    if (cos_i <= ILK_BSDF_EPS) {
        /* The shading normal faces away from wo: the geometric one instead. */
        n = entering ? b->ng : ilk_scale(b->ng, -1.0f);
        cos_i = fabsf(cos_og);
    }
    float cos_t;
    float F = ilk_fresnel_dielectric(cos_i, eta, &cos_t);
    if (u_lobe < F) {
        *wi = ilk_sub(ilk_scale(n, 2.0f * cos_i), wo);
        if (ilk_dot(*wi, b->ng) * cos_og <= 0.0f)
            return false;
        *weight = b->m->specular;
    } else {
        *wi = ilk_normalize(ilk_add(ilk_scale(wo, -1.0f / eta), ilk_scale(n, cos_i / eta - cos_t)));
        if (ilk_dot(*wi, b->ng) * cos_og >= 0.0f)
            return false;
        *weight = ilk_scale(b->m->specular, 1.0f / (eta * eta));
    }
    return weight->x > 0.0f || weight->y > 0.0f || weight->z > 0.0f;
}

/* Draws wi (il_bsdf_sample_dir): glass as above; a mirror reflects about
 * the shading normal (weight: the tint); Phong samples its lobe when
 * u_lobe >= the diffuse probability, else (and diffuse) the cosine lobe;
 * *weight = f cos / pdf and *pdf the density of wi (what ilk_bsdf_eval
 * gives for it; 0 for the delta BSDFs).  False when the sample carries no
 * energy. */
IL_DEVICE_INLINE bool ilk_bsdf_sample(const ilk_bsdf *b, ilk_vec3 wo, float u_lobe, float u1, float u2, ilk_vec3 *wi,
                                      ilk_vec3 *weight, float *pdf)
{
    const ilk_material *m = b->m;
    *pdf = 0.0f;
    if (m->type == ILK_MATERIAL_DIELECTRIC)
        return ilk_dielectric_sample(b, wo, u_lobe, wi, weight);
    ilk_vec3 n;
    float cos_o;
    if (!ilk_bsdf_side(b, wo, &n, &cos_o))
        return false;
    if (m->type == ILK_MATERIAL_MIRROR) {
        *wi = ilk_sub(ilk_scale(n, 2.0f * cos_o), wo);
        if (!(ilk_dot(wo, b->ng) * ilk_dot(*wi, b->ng) > 0.0f))
            return false;
        *weight = m->specular;
        return weight->x > 0.0f || weight->y > 0.0f || weight->z > 0.0f;
    }
    if (m->type == ILK_MATERIAL_PHONG && u_lobe >= m->diffuse_prob)
        *wi = ilk_phong_dir(ilk_sub(ilk_scale(n, 2.0f * cos_o), wo), m->exponent, u1, u2);
    else
        *wi = ilk_cosine_dir(n, u1, u2);
    float cos_i = ilk_dot(*wi, n);
    if (cos_i <= ILK_BSDF_EPS)
        return false;   /* the lobe dipped below the horizon */
    ilk_vec3 f = ilk_bsdf_eval_side(b, n, cos_o, wo, *wi, pdf);
    if (!(*pdf > 0.0f) || !(ilk_dot(wo, b->ng) * ilk_dot(*wi, b->ng) > 0.0f))
        return false;
    *weight = ilk_scale(f, cos_i / *pdf);
    return weight->x > 0.0f || weight->y > 0.0f || weight->z > 0.0f;
}

/* il_sides_agree: wo and wi on the same sides of ng and of ns, or the
 * sample would leak light through the surface (Veach 1997, 5.3.2). */
IL_DEVICE_INLINE bool ilk_sides_agree(const ilk_bsdf *b, ilk_vec3 wo, ilk_vec3 wi)
{
    float g = ilk_dot(wo, b->ng) * ilk_dot(wi, b->ng);
    float s = ilk_dot(wo, b->ns) * ilk_dot(wi, b->ns);
    return (g > 0.0f) == (s > 0.0f) && g != 0.0f;
}

#endif
