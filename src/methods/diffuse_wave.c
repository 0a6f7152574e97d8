/* The Lambertian and Phong vertices of a wave, eight at a time in AVX2
 * lanes (see diffuse_wave.h).
 *
 * The commonest vertex of a scene is a diffuse surface whose light sample
 * lands on a triangle light, a point or spot light, the sun or the sky.  Its light sample is
 * a chain of dependent square roots, divisions and dot products (il_light_sample_at,
 * il_bsdf_eval, the power heuristic, il_shadow_ray), and its next ray
 * another (the shading frame, il_bsdf_sample_dir_cos, il_offset_origin),
 * which one path at a time leave the CPU waiting on each result.  Here the
 * vertices are gathered into lanes and each chain runs once for eight.
 *
 * Every lane does the operations of the scalar code in the same order, each
 * correctly rounded as in scalar SSE (no FMA: compiled for AVX2 by a target
 * attribute, never with -march), so a vertex gets the same bits as the
 * scalar code would give it; tests/validation/test_pt_wavefront.c holds the
 * path tracer's wavefront to its one-path-at-a-time estimator.  Comparisons
 * keep C's treatment of NaN (ordered for <, >, <=, >=; unordered for !=). */
#include <float.h>
#include <math.h>

#include "methods/diffuse_wave.h"

#include "scene/bsdf.h"
#include "scene/lights.h"

#if defined(__x86_64__) && defined(__GNUC__)
#include <immintrin.h>
#define IL_DIFFUSE_AVX2 1
#endif

#ifdef IL_DIFFUSE_AVX2
#define IL_AVX2 __attribute__((target("avx2")))

enum { LANES = 8 };

/* One batch of lanes, structure of arrays.  The vertex: the shading point
 * p, its geometric and shading normals, wo, the throughput, the diffuse
 * albedo, a Phong surface's specular colour, exponent and diffuse-lobe
 * probability, and the cosine-distributed direction drawn for it.  Its light
 * sample (lanes with `nee` set): the triangle (vertices, normal, area,
 * selection probability, radiance, sidedness) and the point sample u.
 * Outputs: whether a shadow ray is cast, the ray and the radiance it
 * carries; whether the path goes on, its throughput, pdf and next ray. */
typedef struct lanes {
    float p[3][LANES], ng[3][LANES], ns[3][LANES], wo[3][LANES], beta[3][LANES], kd[3][LANES];
    float cos_dir[3][LANES];
    float is_phong[LANES], ks[3][LANES], expo[LANES], pd[LANES]; /* Phong lanes' il_bsdf */
    float q0[3][LANES], q1[3][LANES], q2[3][LANES], lng[3][LANES], area[LANES], pmf[LANES];
    float rad[3][LANES], two_sided[LANES], is_point[LANES], is_dir[LANES], is_env[LANES], ux[LANES], uy[LANES];
    float is_spot[LANES], cos_cutoff[LANES], spot_exponent[LANES]; /* a spot (is_point too): q1 its axis */
    float cast[LANES], org[3][LANES], dir[3][LANES], shadow_L[3][LANES];
    float next_ok[LANES], next_beta[3][LANES], next_pdf[LANES], next_org[3][LANES], next_dir[3][LANES];
} lanes;

typedef struct v3x8 {
    __m256 x, y, z;
} v3x8;

IL_AVX2 static inline v3x8 load3(float a[3][LANES])
{
    return (v3x8){_mm256_loadu_ps(a[0]), _mm256_loadu_ps(a[1]), _mm256_loadu_ps(a[2])};
}
IL_AVX2 static inline void store3(float a[3][LANES], v3x8 v)
{
    _mm256_storeu_ps(a[0], v.x);
    _mm256_storeu_ps(a[1], v.y);
    _mm256_storeu_ps(a[2], v.z);
}
IL_AVX2 static inline v3x8 add3(v3x8 a, v3x8 b)
{
    return (v3x8){_mm256_add_ps(a.x, b.x), _mm256_add_ps(a.y, b.y), _mm256_add_ps(a.z, b.z)};
}
IL_AVX2 static inline v3x8 sub3(v3x8 a, v3x8 b)
{
    return (v3x8){_mm256_sub_ps(a.x, b.x), _mm256_sub_ps(a.y, b.y), _mm256_sub_ps(a.z, b.z)};
}
IL_AVX2 static inline v3x8 mul3(v3x8 a, v3x8 b)
{
    return (v3x8){_mm256_mul_ps(a.x, b.x), _mm256_mul_ps(a.y, b.y), _mm256_mul_ps(a.z, b.z)};
}
IL_AVX2 static inline v3x8 scale3(v3x8 a, __m256 s)
{
    return (v3x8){_mm256_mul_ps(a.x, s), _mm256_mul_ps(a.y, s), _mm256_mul_ps(a.z, s)};
}
IL_AVX2 static inline v3x8 neg3(v3x8 a)
{
    const __m256 sign = _mm256_set1_ps(-0.0f);
    return (v3x8){_mm256_xor_ps(a.x, sign), _mm256_xor_ps(a.y, sign), _mm256_xor_ps(a.z, sign)};
}
/* v3_dot's order: (x*x' + y*y') + z*z'. */
IL_AVX2 static inline __m256 dot3(v3x8 a, v3x8 b)
{
    return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(a.x, b.x), _mm256_mul_ps(a.y, b.y)),
                         _mm256_mul_ps(a.z, b.z));
}
/* mask ? a : b, per lane. */
IL_AVX2 static inline __m256 sel(__m256 mask, __m256 a, __m256 b) { return _mm256_blendv_ps(b, a, mask); }
IL_AVX2 static inline v3x8 sel3(__m256 mask, v3x8 a, v3x8 b)
{
    return (v3x8){sel(mask, a.x, b.x), sel(mask, a.y, b.y), sel(mask, a.z, b.z)};
}
IL_AVX2 static inline __m256 fabs8(__m256 a) { return _mm256_andnot_ps(_mm256_set1_ps(-0.0f), a); }
IL_AVX2 static inline __m256 gt0(__m256 a) { return _mm256_cmp_ps(a, _mm256_setzero_ps(), _CMP_GT_OQ); }
IL_AVX2 static inline __m256 is_zero3(v3x8 a)
{
    const __m256 z = _mm256_setzero_ps();
    return _mm256_and_ps(_mm256_and_ps(_mm256_cmp_ps(a.x, z, _CMP_EQ_OQ), _mm256_cmp_ps(a.y, z, _CMP_EQ_OQ)),
                         _mm256_cmp_ps(a.z, z, _CMP_EQ_OQ));
}

/* il_offset_origin: p moved off its surface along n, to dir's side, by the
 * tracer's epsilon grown with the coordinates' magnitude. */
IL_AVX2 static inline v3x8 offset_origin(__m256 epsilon, v3x8 p, v3x8 n, v3x8 dir)
{
    __m256 mag = _mm256_max_ps(fabs8(p.x), _mm256_max_ps(fabs8(p.y), fabs8(p.z)));
    __m256 eps = _mm256_add_ps(epsilon, _mm256_mul_ps(_mm256_mul_ps(mag, _mm256_set1_ps(4.0f)),
                                                      _mm256_set1_ps(FLT_EPSILON)));
    __m256 front = _mm256_cmp_ps(dot3(n, dir), _mm256_setzero_ps(), _CMP_GE_OQ);
    __m256 s = sel(front, eps, _mm256_xor_ps(eps, _mm256_set1_ps(-0.0f)));
    return add3(p, scale3(n, s));
}

/* il_frame_from_normal (Duff et al. 2017, "Building an Orthonormal Basis,
 * Revisited"): the tangents s and t of the frame about n. */
IL_AVX2 static inline void frame8(v3x8 n, v3x8 *fs, v3x8 *ft)
{
    const __m256 one = _mm256_set1_ps(1.0f), minus = _mm256_set1_ps(-0.0f);
    __m256 sign = _mm256_or_ps(_mm256_and_ps(n.z, minus), one);
    __m256 a = _mm256_div_ps(_mm256_set1_ps(-1.0f), _mm256_add_ps(sign, n.z));
    __m256 b = _mm256_mul_ps(_mm256_mul_ps(n.x, n.y), a);
    *fs = (v3x8){_mm256_add_ps(one, _mm256_mul_ps(_mm256_mul_ps(_mm256_mul_ps(sign, n.x), n.x), a)),
                 _mm256_mul_ps(sign, b), _mm256_mul_ps(_mm256_xor_ps(sign, minus), n.x)};
    *ft = (v3x8){b, _mm256_add_ps(sign, _mm256_mul_ps(_mm256_mul_ps(n.y, n.y), a)), _mm256_xor_ps(n.y, minus)};
}

/* opaque_eval_local's Phong terms for the Phong lanes (the others keep f
 * and pdf): wi_l and wo_l in the local frame flipped to wo's side, the lobe
 * cos^n of the angle between wi_l and wo_l's mirror image (powf per lane,
 * the scalar code's own call), f += ks (n+2)/(2 pi) lobe, and the pdf mixed
 * with the lobe's by the diffuse-lobe probability (Lafortune & Willems
 * 1994; one-sample MIS over lobes, Veach 1997 9.2.4). */
IL_AVX2 static void phong8(lanes *l, v3x8 wi_l, __m256 wo_lx, __m256 wo_ly, __m256 wo_lz, v3x8 *f,
                           __m256 *pdf)
{
    const __m256 one = _mm256_set1_ps(1.0f), minus = _mm256_set1_ps(-0.0f);
    const __m256 inv_2pi = _mm256_set1_ps(IL_INV_2PI);
    __m256 cos_alpha = _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(wi_l.x, _mm256_xor_ps(wo_lx, minus)),
                                                   _mm256_mul_ps(wi_l.y, _mm256_xor_ps(wo_ly, minus))),
                                     _mm256_mul_ps(wi_l.z, wo_lz));
    float ca[LANES], lobe[LANES];
    _mm256_storeu_ps(ca, cos_alpha);
    for (int k = 0; k < LANES; k++)
        lobe[k] = l->is_phong[k] != 0.0f && ca[k] > 0.0f ? powf(il_minf(ca[k], 1.0f), l->expo[k]) : 0.0f;
    __m256 lb = _mm256_loadu_ps(lobe), n = _mm256_loadu_ps(l->expo), pd = _mm256_loadu_ps(l->pd);
    __m256 is_phong = _mm256_loadu_ps(l->is_phong);
    __m256 kf = _mm256_mul_ps(_mm256_mul_ps(_mm256_add_ps(n, _mm256_set1_ps(2.0f)), inv_2pi), lb);
    v3x8 fp = add3(*f, scale3(load3(l->ks), kf));
    __m256 pp = _mm256_add_ps(_mm256_mul_ps(pd, *pdf),
                              _mm256_mul_ps(_mm256_mul_ps(_mm256_mul_ps(_mm256_sub_ps(one, pd), _mm256_add_ps(n, one)),
                                                          inv_2pi),
                                            lb));
    *f = sel3(is_phong, fp, *f);
    *pdf = sel(is_phong, pp, *pdf);
}

/* A spot light's profile for the spot lanes (il_light_sample_at): c the
 * cosine between its axis and the direction to the shading point; the
 * lane's sample is kept when c is not below the cut-off and, with a
 * positive exponent, above zero; its intensity is then scaled by c^n
 * (powf per lane, the scalar code's own call; 1 without an exponent). */
IL_AVX2 static __m256 spot8(const lanes *l, __m256 c, __m256 *keep)
{
    const __m256 zero = _mm256_setzero_ps(), all = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
    __m256 n = _mm256_loadu_ps(l->spot_exponent);
    __m256 below = _mm256_cmp_ps(c, _mm256_loadu_ps(l->cos_cutoff), _CMP_LT_OQ);
    __m256 behind = _mm256_and_ps(gt0(n), _mm256_cmp_ps(c, zero, _CMP_LE_OQ));
    *keep = _mm256_xor_ps(_mm256_or_ps(below, behind), all);
    float cc[LANES], keep_[LANES], scale[LANES];
    _mm256_storeu_ps(cc, c);
    _mm256_storeu_ps(keep_, *keep);
    for (int k = 0; k < LANES; k++) /* other lanes' exponent is 0: no powf */
        scale[k] = keep_[k] != 0.0f && l->spot_exponent[k] > 0.0f ? powf(cc[k], l->spot_exponent[k]) : 1.0f;
    return _mm256_loadu_ps(scale);
}

/* The light sample of eight lanes: the next-event block of il_pt_step_at
 * (IL_DIFFUSE_NEE_MIS) or il_direct_light_sample (IL_DIFFUSE_NEE_PLAIN). */
IL_AVX2 static void nee8(lanes *l, float epsilon, il_diffuse_nee mode)
{
    const __m256 zero = _mm256_setzero_ps(), one = _mm256_set1_ps(1.0f);
    const __m256 bsdf_eps = _mm256_set1_ps(1e-7f), inv_pi = _mm256_set1_ps(IL_INV_PI);
    v3x8 p = load3(l->p), ng = load3(l->ng), ns = load3(l->ns), wo = load3(l->wo);

    const __m256 is_point = _mm256_loadu_ps(l->is_point), is_dir = _mm256_loadu_ps(l->is_dir);
    const __m256 is_delta = _mm256_or_ps(is_point, is_dir), all = _mm256_castsi256_ps(_mm256_set1_epi32(-1));
    /* A direction given in the record: the sun's, or the environment's
     * sample (drawn by fill_light); the shadow ray then has no end. */
    const __m256 is_env = _mm256_loadu_ps(l->is_env), is_far = _mm256_or_ps(is_dir, is_env);
    /* il_light_sample_at.  A triangle: il_sample_triangle, then the point
     * p0 b0 + p1 b1 + p2 b2 (il_scene_point); a point or spot light: its
     * position. */
    __m256 ux = _mm256_loadu_ps(l->ux), uy = _mm256_loadu_ps(l->uy);
    __m256 hx = _mm256_mul_ps(_mm256_set1_ps(0.5f), ux), hy = _mm256_mul_ps(_mm256_set1_ps(0.5f), uy);
    __m256 upper = _mm256_cmp_ps(ux, uy, _CMP_LT_OQ);
    __m256 b1 = sel(upper, hx, _mm256_sub_ps(ux, hy));
    __m256 b2 = sel(upper, _mm256_sub_ps(uy, hx), hy);
    __m256 b0 = _mm256_sub_ps(_mm256_sub_ps(one, b1), b2);
    v3x8 q0 = load3(l->q0);
    v3x8 q = add3(add3(scale3(q0, b0), scale3(load3(l->q1), b1)), scale3(load3(l->q2), b2));
    q = sel3(is_point, q0, q);
    v3x8 lng = load3(l->lng);
    /* aim_at, or the direction given in q0. */
    v3x8 d = sub3(q, p);
    __m256 dist2 = dot3(d, d);
    __m256 dist = _mm256_sqrt_ps(dist2);
    v3x8 wi = sel3(is_far, q0, scale3(d, _mm256_div_ps(one, dist)));
    /* A triangle's radiance towards p and its pdf: selection times
     * area_to_solid_angle; a point light's I / d^2 (pbrt-v4 12.1); a
     * directional light's irradiance; delta lights' pdf the selection's;
     * the environment's radiance and pdf as fill_light drew them. */
    v3x8 le = load3(l->rad);
    __m256 pmf = _mm256_loadu_ps(l->pmf);
    __m256 facing = _mm256_or_ps(_mm256_loadu_ps(l->two_sided), gt0(dot3(lng, neg3(wi))));
    v3x8 rad_tri = sel3(facing, le, (v3x8){zero, zero, zero});
    __m256 c = fabs8(dot3(lng, wi));
    __m256 area = _mm256_loadu_ps(l->area);
    __m256 pdf_area = sel(_mm256_and_ps(gt0(c), gt0(area)), _mm256_div_ps(dist2, _mm256_mul_ps(area, c)), zero);
    __m256 pdf_tri = _mm256_mul_ps(pmf, pdf_area);
    __m256 finite = _mm256_cmp_ps(fabs8(pdf_tri), _mm256_set1_ps(INFINITY), _CMP_LT_OQ);
    __m256 ok_tri = _mm256_and_ps(_mm256_and_ps(gt0(pdf_tri), finite), _mm256_xor_ps(is_zero3(rad_tri), all));
    /* A point light's 1 / d^2, for a spot times its profile. */
    __m256 point_scale = _mm256_div_ps(one, dist2);
    const __m256 is_spot = _mm256_loadu_ps(l->is_spot);
    __m256 spot_ok = all;
    if (_mm256_movemask_ps(is_spot)) {
        __m256 keep;
        __m256 profile = spot8(l, _mm256_xor_ps(dot3(load3(l->q1), wi), _mm256_set1_ps(-0.0f)), &keep);
        point_scale = sel(is_spot, _mm256_mul_ps(point_scale, profile), point_scale);
        spot_ok = sel(is_spot, keep, all);
    }
    v3x8 rad = sel3(is_point, scale3(le, point_scale), sel3(is_far, le, rad_tri));
    __m256 pdf = sel(_mm256_or_ps(is_delta, is_env), pmf, pdf_tri);
    /* Directional: always; the environment: a pdf above zero; a point
     * light: p not on it (a spot: also p inside its cone); a triangle: also
     * a usable pdf and light towards p. */
    __m256 ok = _mm256_or_ps(_mm256_or_ps(is_dir, _mm256_and_ps(is_env, gt0(pdf))),
                             _mm256_and_ps(_mm256_andnot_ps(is_env, gt0(dist2)), _mm256_or_ps(is_point, ok_tri)));
    ok = _mm256_and_ps(ok, spot_ok);
    if (mode == IL_DIFFUSE_NEE_PLAIN) /* il_direct_light_sample's own tests */
        ok = _mm256_and_ps(ok, _mm256_and_ps(gt0(pdf), _mm256_xor_ps(is_zero3(rad), all)));

    /* il_sides_agree(surf, wo, wi) */
    __m256 wo_ng = dot3(wo, ng), wo_ns = dot3(wo, ns), wi_ns = dot3(wi, ns);
    __m256 g = _mm256_mul_ps(wo_ng, dot3(wi, ng));
    __m256 n = _mm256_mul_ps(wo_ns, wi_ns);
    __m256 agree = _mm256_andnot_ps(_mm256_xor_ps(gt0(g), gt0(n)), _mm256_cmp_ps(g, zero, _CMP_NEQ_UQ));
    ok = _mm256_and_ps(ok, agree);

    /* il_bsdf_eval: same geometric side (g > 0), wo above the flipped
     * shading frame, wi above it too; f = kd/pi, pdf = cos/pi, and a Phong
     * lane's lobe added (phong8). */
    __m256 flip = _mm256_cmp_ps(wo_ns, zero, _CMP_LT_OQ);
    __m256 wo_z = sel(flip, _mm256_xor_ps(wo_ns, _mm256_set1_ps(-0.0f)), wo_ns);
    __m256 wi_z = sel(flip, _mm256_xor_ps(wi_ns, _mm256_set1_ps(-0.0f)), wi_ns);
    __m256 lit = _mm256_and_ps(_mm256_and_ps(gt0(g), _mm256_cmp_ps(wo_z, bsdf_eps, _CMP_GT_OQ)),
                               _mm256_cmp_ps(wi_z, bsdf_eps, _CMP_NLE_UQ));
    v3x8 f = scale3(load3(l->kd), inv_pi);
    __m256 bsdf_pdf = sel(gt0(wi_z), _mm256_mul_ps(wi_z, inv_pi), zero);
    if (_mm256_movemask_ps(_mm256_loadu_ps(l->is_phong))) {
        v3x8 fs, ft;
        frame8(ns, &fs, &ft);
        phong8(l, (v3x8){dot3(wi, fs), dot3(wi, ft), wi_z}, dot3(wo, fs), dot3(wo, ft), wo_z, &f, &bsdf_pdf);
    }
    f = sel3(lit, f, (v3x8){zero, zero, zero});
    bsdf_pdf = sel(lit, bsdf_pdf, zero);
    __m256 cos_i = fabs8(wi_ns);
    ok = _mm256_andnot_ps(is_zero3(f), ok);
    __m256 w = one;
    if (mode == IL_DIFFUSE_NEE_MIS) {
        /* The power heuristic (Veach 1997, 9.2.4) for the light sample. */
        __m256 f2 = _mm256_mul_ps(pdf, pdf), g2 = _mm256_mul_ps(bsdf_pdf, bsdf_pdf);
        __m256 sum = _mm256_add_ps(f2, g2);
        w = sel(is_delta, one, sel(gt0(sum), _mm256_div_ps(f2, sum), zero));
        ok = _mm256_and_ps(ok, _mm256_and_ps(gt0(w), gt0(cos_i)));
    } else {
        ok = _mm256_and_ps(ok, _mm256_cmp_ps(cos_i, zero, _CMP_NLE_UQ)); /* !(cos_i <= 0) */
    }

    /* il_shadow_ray(p, ng, q, lng) (a point or spot light's lng is zero: its
     * target is q itself); towards a directional light a ray along wi
     * without end.  And what the ray carries. */
    __m256 eps = _mm256_set1_ps(epsilon);
    v3x8 o = offset_origin(eps, p, ng, d);
    v3x8 target = sel3(is_zero3(lng), q, offset_origin(eps, q, lng, neg3(d)));
    store3(l->org, sel3(is_far, offset_origin(eps, p, ng, wi), o));
    store3(l->dir, sel3(is_far, wi, sub3(target, o)));
    if (mode == IL_DIFFUSE_NEE_MIS)
        store3(l->shadow_L, scale3(mul3(load3(l->beta), mul3(f, rad)), _mm256_div_ps(_mm256_mul_ps(cos_i, w), pdf)));
    else
        store3(l->shadow_L, scale3(mul3(f, rad), _mm256_div_ps(cos_i, pdf)));
    _mm256_storeu_ps(l->cast, ok);
}

/* The BSDF sample of eight lanes: the shading frame, il_bsdf_sample_dir_cos
 * with the drawn cosine direction (a Phong lane's diffuse lobe: the driver
 * leaves its glossy lobe to the scalar code), il_sides_agree, the
 * throughput and the next ray. */
IL_AVX2 static void next8(lanes *l, float epsilon)
{
    const __m256 zero = _mm256_setzero_ps(), minus = _mm256_set1_ps(-0.0f);
    const __m256 bsdf_eps = _mm256_set1_ps(1e-7f), inv_pi = _mm256_set1_ps(IL_INV_PI);
    v3x8 p = load3(l->p), ng = load3(l->ng), n = load3(l->ns), wo = load3(l->wo);
    v3x8 fs, ft;
    frame8(n, &fs, &ft);
    /* opaque_local: wo above the frame flipped to its side */
    __m256 wo_z = dot3(wo, n);
    __m256 flip = _mm256_cmp_ps(wo_z, zero, _CMP_LT_OQ);
    wo_z = sel(flip, _mm256_xor_ps(wo_z, minus), wo_z);
    __m256 ok = _mm256_cmp_ps(wo_z, bsdf_eps, _CMP_GT_OQ);
    /* The cosine-distributed direction, its f and pdf (opaque_eval_local) */
    v3x8 wl = load3(l->cos_dir);
    ok = _mm256_and_ps(ok, _mm256_cmp_ps(wl.z, bsdf_eps, _CMP_NLE_UQ));
    v3x8 f = scale3(load3(l->kd), inv_pi);
    __m256 pdf = sel(gt0(wl.z), _mm256_mul_ps(wl.z, inv_pi), zero);
    if (_mm256_movemask_ps(_mm256_loadu_ps(l->is_phong)))
        phong8(l, wl, dot3(wo, fs), dot3(wo, ft), wo_z, &f, &pdf);
    ok = _mm256_and_ps(ok, gt0(pdf));
    __m256 z = sel(flip, _mm256_xor_ps(wl.z, minus), wl.z);
    v3x8 wi = add3(add3(scale3(fs, wl.x), scale3(ft, wl.y)), scale3(n, z));
    __m256 wo_ng = dot3(wo, ng), wi_ng = dot3(wi, ng);
    __m256 g = _mm256_mul_ps(wo_ng, wi_ng);
    ok = _mm256_and_ps(ok, gt0(g)); /* same_geometric_side */
    v3x8 weight = scale3(f, _mm256_div_ps(wl.z, pdf));
    ok = _mm256_andnot_ps(is_zero3(weight), ok);
    /* il_sides_agree(surf, wo, wi): g as above */
    __m256 sn = _mm256_mul_ps(dot3(wo, n), dot3(wi, n));
    ok = _mm256_and_ps(ok, _mm256_andnot_ps(_mm256_xor_ps(gt0(g), gt0(sn)), _mm256_cmp_ps(g, zero, _CMP_NEQ_UQ)));
    _mm256_storeu_ps(l->next_ok, ok);
    store3(l->next_beta, mul3(load3(l->beta), weight));
    _mm256_storeu_ps(l->next_pdf, pdf);
    store3(l->next_org, offset_origin(_mm256_set1_ps(epsilon), p, ng, wi));
    store3(l->next_dir, wi);
}

static void put3(float a[3][LANES], int k, il_vec3 v)
{
    a[0][k] = v.x;
    a[1][k] = v.y;
    a[2][k] = v.z;
}

/* Lane k's vertex inputs. */
static void fill_vertex(const il_scene *s, const il_diffuse_in *in, lanes *l, int k)
{
    const il_surface *surf = in->surf;
    put3(l->p, k, surf->p);
    put3(l->ng, k, surf->ng);
    put3(l->ns, k, surf->ns);
    put3(l->wo, k, in->wo);
    put3(l->beta, k, in->beta);
    const il_material *m = surf->material;
    if (m->type == IL_MATERIAL_PHONG) {
        il_bsdf b; /* its albedos scaled for energy conservation, its lobe choice */
        il_bsdf_init(&b, s, surf);
        put3(l->kd, k, b.diffuse);
        put3(l->ks, k, b.specular);
        l->expo[k] = b.exponent;
        l->pd[k] = b.diffuse_prob;
        l->is_phong[k] = -1.0f; /* a mask: the sign bit */
    } else {
        il_vec3 kd = m->diffuse_texture ? il_material_diffuse(s, m, surf->uv) : m->diffuse;
        put3(l->kd, k, v3_max(kd, v3s(0.0f))); /* il_bsdf_init's */
        put3(l->ks, k, v3s(0.0f));
        l->expo[k] = 0.0f;
        l->pd[k] = 1.0f;
        l->is_phong[k] = 0.0f;
    }
    put3(l->cos_dir, k, in->cos_dir);
}

/* Lane k's light sample inputs (the record of the light u_select picks);
 * returns its kind, IL_LREC_NONE when nee8 cannot take it (then its
 * results are never read). */
static il_lrec_kind fill_light(const il_scene *s, const il_diffuse_in *in, lanes *l, int k)
{
    static const il_light_rec none = {.kind = IL_LREC_NONE};
    const il_light_rec *r = s->num_lights > 0 ? &s->light_recs[il_light_select(s, in->u_select)] : &none;
    put3(l->q0, k, r->p0);
    put3(l->q1, k, r->p1);
    put3(l->q2, k, r->p2);
    put3(l->lng, k, r->ng);
    put3(l->rad, k, r->radiance);
    l->area[k] = r->area;
    l->pmf[k] = r->pmf;
    /* Masks: the sign bit set. */
    l->two_sided[k] = r->two_sided ? -1.0f : 0.0f;
    l->is_point[k] = r->kind == IL_LREC_POINT || r->kind == IL_LREC_SPOT ? -1.0f : 0.0f;
    l->is_spot[k] = r->kind == IL_LREC_SPOT ? -1.0f : 0.0f;
    l->cos_cutoff[k] = r->cos_cutoff;
    l->spot_exponent[k] = r->spot_exponent;
    l->is_dir[k] = r->kind == IL_LREC_DIRECTIONAL ? -1.0f : 0.0f;
    l->is_env[k] = r->kind == IL_LREC_ENVIRONMENT ? -1.0f : 0.0f;
    if (r->kind == IL_LREC_ENVIRONMENT) {
        /* il_light_sample_at's draw: the direction, its radiance and pdf. */
        float pdf_dir;
        il_vec3 wi;
        put3(l->rad, k, il_environment_sample_at(s, in->surf->p, in->u_light, &wi, &pdf_dir));
        put3(l->q0, k, wi);
        l->pmf[k] = r->pmf * pdf_dir;
    } else if (r->kind == IL_LREC_DIRECTIONAL && r->cos_cutoff < 1.0f) {
        /* il_light_sample_at's draw over the light's disc. */
        float scale;
        put3(l->q0, k, il_directional_sample(r->p0, r->cos_cutoff, in->u_light, &scale));
        put3(l->rad, k, v3_scale(r->radiance, scale));
    }
    l->ux[k] = in->u_light.x;
    l->uy[k] = in->u_light.y;
    return r->kind;
}

/* Lane k takes lane 0's inputs: the unused lanes of a short batch. */
static void copy_lane0(lanes *l, int k)
{
    float(*v3s_[])[LANES] = {l->p, l->ng, l->ns, l->wo, l->beta, l->kd, l->ks, l->cos_dir,
                             l->q0, l->q1, l->q2, l->lng, l->rad};
    for (size_t i = 0; i < sizeof v3s_ / sizeof v3s_[0]; i++)
        for (int c = 0; c < 3; c++)
            v3s_[i][c][k] = v3s_[i][c][0];
    l->area[k] = l->area[0], l->pmf[k] = l->pmf[0], l->two_sided[k] = l->two_sided[0];
    l->is_point[k] = l->is_point[0], l->is_dir[k] = l->is_dir[0], l->is_env[k] = l->is_env[0];
    l->is_spot[k] = l->is_spot[0], l->cos_cutoff[k] = l->cos_cutoff[0];
    l->spot_exponent[k] = l->spot_exponent[0];
    l->is_phong[k] = l->is_phong[0], l->expo[k] = l->expo[0], l->pd[k] = l->pd[0];
    l->ux[k] = l->ux[0], l->uy[k] = l->uy[0];
}

static il_vec3 get3(const float a[3][LANES], int k) { return v3(a[0][k], a[1][k], a[2][k]); }

/* Lane k's results. */
static void store_lane(const lanes *l, il_lrec_kind light, bool next, il_diffuse_out *out, int k)
{
    out->nee_done = light != IL_LREC_NONE;
    out->shadow = out->nee_done && l->cast[k] != 0.0f;
    if (out->shadow) {
        /* il_shadow_ray's end short of the light, or none for a direction */
        float tmax = light == IL_LREC_DIRECTIONAL || light == IL_LREC_ENVIRONMENT ? INFINITY : 1.0f - 1e-4f;
        out->shadow_ray = (il_ray){.org = get3(l->org, k), .tmin = 0.0f, .dir = get3(l->dir, k),
                                   .tmax = tmax};
        out->shadow_L = get3(l->shadow_L, k);
    }
    out->next_done = next;
    out->next_ok = l->next_ok[k] != 0.0f;
    out->next_beta = get3(l->next_beta, k);
    out->next_pdf = l->next_pdf[k];
    out->next_ray = (il_ray){.org = get3(l->next_org, k), .tmin = 0.0f, .dir = get3(l->next_dir, k),
                             .tmax = INFINITY};
}

IL_AVX2 static void diffuse_wave_avx2(const il_scene *s, const il_diffuse_in *in,
                                      il_diffuse_out *const *out, uint32_t n, il_diffuse_nee nee)
{
    lanes l;
    uint32_t lane_vertex[LANES];
    il_lrec_kind lane_light[LANES];
    bool lane_next[LANES];
    float epsilon = il_trace_epsilon(s->tracer);
    int k = 0;
    for (uint32_t i = 0; i <= n; i++) {
        if (i < n) {
            il_material_type type = in[i].surf->material->type;
            if (type != IL_MATERIAL_DIFFUSE && type != IL_MATERIAL_PHONG)
                continue;
            fill_vertex(s, &in[i], &l, k);
            /* il_bsdf_sample_dir_cos's lobe choice: the glossy lobe is not ours */
            lane_next[k] = type == IL_MATERIAL_DIFFUSE || in[i].u_lobe < l.pd[k];
            lane_light[k] = fill_light(s, &in[i], &l, k);
            lane_vertex[k++] = i;
            if (k < LANES)
                continue;
        }
        if (k == 0)
            break;
        for (int e = k; e < LANES; e++)
            copy_lane0(&l, e);
        nee8(&l, epsilon, nee);
        next8(&l, epsilon);
        for (int e = 0; e < k; e++)
            store_lane(&l, lane_light[e], lane_next[e], out[lane_vertex[e]], e);
        k = 0;
    }
}
#endif

void il_diffuse_wave(const il_scene *s, const il_diffuse_in *in, il_diffuse_out *const *out,
                     uint32_t n, il_diffuse_nee nee)
{
    for (uint32_t i = 0; i < n; i++)
        out[i]->nee_done = out[i]->shadow = out[i]->next_done = out[i]->next_ok = false;
#ifdef IL_DIFFUSE_AVX2
    if (__builtin_cpu_supports("avx2"))
        diffuse_wave_avx2(s, in, out, n, nee);
#else
    (void)s, (void)in, (void)nee;
#endif
}
