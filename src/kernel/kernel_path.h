/* One path-traced camera sample, shared by the CPU (gcc) and the GPU
 * megakernel (src/cuda/pt_kernel.cu): pinhole camera as scene/camera.c,
 * Lambertian, normalised Phong, mirror and glass surfaces
 * (kernel/kernel_bsdf.h, the CPU's scene/bsdf.c) with interpolated shading
 * normals as il_scene_surface,
 * front-face (or two-sided) area emitters, point, spot and directional
 * lights and an environment, uniform or a map.  At every vertex next-event
 * estimation picks one light of the path-tracing light table (emissive
 * triangles, the delta lights and an environment map, by power, as
 * scene/lights.c) and BSDF sampling continues the path (mirror and glass
 * vertices skip NEE: only BSDF sampling can find what they see).  Area
 * emission and an environment map are reached both ways: by NEE, and by a
 * BSDF-sampled ray that hits the emitter or escapes; after a non-delta
 * bounce the two are weighted by the power heuristic (Veach 1997, 9.2.4;
 * pbrt-v4 13.4.2) as in the CPU path tracer, on camera rays and after
 * mirror or glass bounces the BSDF ray counts alone.  Delta lights are
 * reachable by NEE only.  A map is sampled by its own importance-sampling
 * table (image/envmap_sample.c); a constant sky is
 * found by BSDF sampling alone: the CPU's uniform directions towards it
 * are never better than the cosine or Phong lobe, and its share of the
 * light choice would be taken from the other lights (on the test scene of
 * a sun and a sky the noise doubled).  Random numbers: the CPU's Owen-scrambled Sobol sampler
 * (kernel/kernel_sobol.h, the same numbers as core/sampler.c for a (seed,
 * pixel, sample, dimension)), the camera jitter in dimensions 0-1 and three
 * pairs per vertex (light choice and BSDF lobe choice, point on the light,
 * bounce direction), a fourth from the fourth vertex on for the Russian
 * roulette, so the result does not depend on how pixels are split among
 * threads or GPU blocks.  The CPU path tracer spends its dimensions
 * differently (MIS, Russian roulette), so images agree in expectation, not
 * bit for bit.  The PCG32 stream below (ilk_rng) is for the photon
 * kernels. */
#ifndef IL_KERNEL_PATH_H
#define IL_KERNEL_PATH_H

#include "kernel/kernel_bsdf.h"
#include "kernel/kernel_bvh.h"
#include "kernel/kernel_sobol.h"

/* ilk_light.kind */
#define ILK_LIGHT_AREA 0u
#define ILK_LIGHT_POINT 1u
#define ILK_LIGHT_SPOT 2u
#define ILK_LIGHT_DIRECTIONAL 3u
#define ILK_LIGHT_ENVIRONMENT 4u

/* One entry of the path kernel's light table (scene/lights.c's il_light). */
typedef struct ilk_light {
    ilk_vec3 position;     /* POINT, SPOT */
    uint32_t kind;         /* ILK_LIGHT_* */
    ilk_vec3 direction;    /* SPOT, DIRECTIONAL: unit, the way light travels */
    uint32_t tri;          /* AREA: index into tris */
    ilk_vec3 intensity;    /* POINT, SPOT: W/sr; DIRECTIONAL: irradiance W/m^2 */
    float cos_cutoff;      /* SPOT; DIRECTIONAL: cos of its disc's angular radius (1: a point) */
    float spot_exponent;   /* SPOT */
    float pad[3];
} ilk_light;

/* A directional light's disc as the camera sees it (scene.h's
 * il_light_disc); a scene has at most ILK_MAX_DISCS (kernel_scene.c). */
#define ILK_MAX_DISCS 4u
typedef struct ilk_disc {
    ilk_vec3 towards;      /* unit, towards the disc's centre */
    float sin2_radius;     /* sin^2 of its angular radius */
    ilk_vec3 radiance;
    float pad;
} ilk_disc;

/* The vertex normals of one triangle (of tris[i], leaf order), as the mesh
 * gives them; all zero when it has none. */
typedef struct ilk_tri_normals {
    ilk_vec3 n[3];
} ilk_tri_normals;

/* The texture coordinates of one triangle's vertices (of tris[i]), all
 * zero when its mesh has none. */
typedef struct ilk_tri_uvs {
    float u[3], v[3];
} ilk_tri_uvs;

/* A texture of linear RGB floats, rows top to bottom, at texels[offset ..]. */
typedef struct ilk_texture {
    uint32_t width, height;
    uint64_t offset;
} ilk_texture;

typedef struct ilk_camera {
    ilk_vec3 position, forward, right, up;
    float tan_half_x, tan_half_y, inv_width, inv_height;
} ilk_camera;

/* Everything a path needs, as flat arrays (host or device pointers).  The
 * material of tris[i] is materials[tris[i].pad] (bvh_build.c stores it). */
typedef struct ilk_scene {
    ilk_bvh bvh;
    const ilk_material *materials;
    const uint32_t *lights;        /* emissive triangles (indices into tris), for the photon kernels */
    const float *light_cdf;        /* num_lights + 1 entries, by power */
    uint32_t num_lights;
    float epsilon;                 /* ray offset, as il_trace_epsilon */
    /* The path kernel's light table: emissive triangles and point, spot and
     * directional lights, chosen by power (pt_light_cdf, num_pt_lights + 1). */
    const ilk_light *pt_lights;
    const float *pt_light_cdf;
    uint32_t num_pt_lights;
    uint32_t has_environment;      /* a sky: uniform radiance `environment`, or the map below */
    ilk_vec3 environment;
    /* An environment map (NULL: none) as a latitude-longitude map of
     * env_width x env_height texels (3 floats each, rows from +y down; an
     * angular or cross map resampled to one), turned by the scene's
     * rotation about +y (image/envmap.h's il_envmap_to_local). */
    const float *env_texels;
    uint32_t env_width, env_height;
    float env_cos_rot, env_sin_rot;
    /* Its importance sampling (image/envmap_sample.c's table; NULL
     * without a map): a piecewise-constant density over
     * env_grid_w x env_grid_h lat-long cells, as CDFs: the rows' marginal
     * (env_grid_h + 1 entries), then each row's conditional (env_grid_w +
     * 1 entries each).  env_light_pmf: the environment's probability in
     * the light table (0: not in it). */
    const float *env_cdf;
    uint32_t env_grid_w, env_grid_h;
    float env_light_pmf;
    /* Per triangle (of tris), its probability in the light table: 0 unless
     * it emits (NULL: no triangle emits). */
    const float *tri_light_pmf;
    /* The discs of directional lights (the sun), which camera rays and
     * mirror or glass chains from the camera see (il_background_radiance). */
    ilk_disc discs[ILK_MAX_DISCS];
    uint32_t num_discs;
    const ilk_tri_normals *normals; /* per triangle; NULL when no mesh has normals */
    const ilk_tri_uvs *uvs;        /* per triangle; NULL when no material has a texture */
    const ilk_texture *textures;
    const float *texels;           /* every texture's texels, 3 floats each */
    ilk_camera camera;
    uint32_t width, height, max_depth;
    uint64_t seed;
} ilk_scene;

/* PCG32 (O'Neill 2014, pcg-random.org, "XSH RR"), as core/rng.h. */
typedef struct ilk_rng { uint64_t state, inc; } ilk_rng;

IL_DEVICE_INLINE uint32_t ilk_rng_next(ilk_rng *r)
{
    uint64_t old = r->state;
    r->state = old * 6364136223846793005ULL + r->inc;
    uint32_t xs = (uint32_t)(((old >> 18u) ^ old) >> 27u);
    uint32_t rot = (uint32_t)(old >> 59u);
    return (xs >> rot) | (xs << ((32u - rot) & 31u));
}
/* [0, 1): the top 24 bits. */
IL_DEVICE_INLINE float ilk_rng_float(ilk_rng *r) { return (float)(ilk_rng_next(r) >> 8) * (1.0f / 16777216.0f); }

/* SplitMix64 finaliser (Steele et al. 2014) to key streams. */
IL_DEVICE_INLINE uint64_t ilk_hash64(uint64_t x)
{
    x += 0x9e3779b97f4a7c15ULL;
    x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
    x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
    return x ^ (x >> 31);
}

IL_DEVICE_INLINE ilk_rng ilk_rng_for(uint64_t seed, uint64_t pixel, uint32_t sample)
{
    ilk_rng r;
    r.state = 0;
    r.inc = (ilk_hash64(seed ^ (pixel << 20) ^ sample) << 1u) | 1u;
    ilk_rng_next(&r);
    r.state += ilk_hash64(pixel * 0x100000001b3ULL + sample + (seed << 40));
    ilk_rng_next(&r);
    return r;
}

/* The light with cdf[i] <= u < cdf[i+1] (binary search). */
IL_DEVICE_INLINE uint32_t ilk_pick_light(const float *cdf, uint32_t n, float u)
{
    uint32_t lo = 0, hi = n;
    while (hi - lo > 1) {
        uint32_t mid = (lo + hi) / 2;
        if (cdf[mid] <= u)
            lo = mid;
        else
            hi = mid;
    }
    return lo;
}

/* The geometric and shading normals of triangle `tri` at barycentrics
 * (b1, b2), as il_scene_surface: the normals interpolated when the mesh has
 * them, and the geometric normal then turned to their side (authored
 * normals say which side is the front). */
IL_DEVICE_INLINE void ilk_surface_normals(const ilk_scene *sc, uint32_t tri, float b1, float b2, ilk_vec3 *ng,
                                          ilk_vec3 *ns)
{
    const ilk_tri *t = &sc->bvh.tris[tri];
    *ng = ilk_normalize(ilk_cross(t->e1, t->e2));
    *ns = *ng;
    if (!sc->normals)
        return;
    const ilk_tri_normals *tn = &sc->normals[tri];
    float b0 = 1.0f - b1 - b2;
    ilk_vec3 n = ilk_add(ilk_add(ilk_scale(tn->n[0], b0), ilk_scale(tn->n[1], b1)), ilk_scale(tn->n[2], b2));
    float l = sqrtf(ilk_dot(n, n));
    if (l > 1e-6f && l < INFINITY) {
        *ns = ilk_scale(n, 1.0f / l);
        if (ilk_dot(*ns, *ng) < 0.0f)
            *ng = ilk_scale(*ng, -1.0f);
    }
}

/* The area of triangle t. */
IL_DEVICE_INLINE float ilk_tri_area(const ilk_tri *t)
{
    ilk_vec3 c = ilk_cross(t->e1, t->e2);
    return 0.5f * sqrtf(ilk_dot(c, c));
}

/* Texel i of an array of RGB floats. */
IL_DEVICE_INLINE ilk_vec3 ilk_texel(const float *t, uint64_t i)
{
    return ilk_v3(t[3 * i], t[3 * i + 1], t[3 * i + 2]);
}

/* World direction d in the map's own frame (its turn about +y undone, as
 * image/envmap.h's il_envmap_to_local), returned, and there its
 * latitude-longitude coordinates (u, v) in [0, 1] (il_envmap_dir_to_uv);
 * *st = |d| sin theta. */
IL_DEVICE_INLINE ilk_vec3 ilk_environment_uv(const ilk_scene *sc, ilk_vec3 d, float *u, float *v, float *st)
{
    float c = sc->env_cos_rot, s = sc->env_sin_rot;
    ilk_vec3 l = ilk_v3(d.x * c - d.z * s, d.y, d.x * s + d.z * c);
    *st = sqrtf(l.x * l.x + l.z * l.z);
    float theta = atan2f(*st, l.y), phi = atan2f(l.x, -l.z);
    *u = ilk_minf(ilk_maxf(0.5f + phi * ILK_INV_2PI, 0.0f), 1.0f);
    *v = ilk_minf(ilk_maxf(theta * ILK_INV_PI, 0.0f), 1.0f);
    return l;
}

/* The radiance arriving from world direction d: the uniform sky, or the
 * map's bilinear value as image/envmap.c's il_envmap_lookup reads a
 * latitude-longitude map (u wraps around, v is clamped). */
IL_DEVICE_INLINE ilk_vec3 ilk_environment(const ilk_scene *sc, ilk_vec3 d)
{
    if (!sc->env_texels)
        return sc->environment;
    float u, v, st;
    ilk_vec3 l = ilk_environment_uv(sc, d, &u, &v, &st);
    if (!(fabsf(l.x) < INFINITY && fabsf(l.y) < INFINITY && fabsf(l.z) < INFINITY) ||
        (l.x == 0.0f && l.y == 0.0f && l.z == 0.0f))
        return ilk_v3(0, 0, 0);
    uint32_t w = sc->env_width, h = sc->env_height;
    float x = u * (float)w - 0.5f, fx = floorf(x), tx = x - fx;
    long k = (long)fx % (long)w;
    if (k < 0)
        k += w;
    uint32_t x0 = (uint32_t)k, x1 = x0 + 1 == w ? 0 : x0 + 1;
    float y = v * (float)h - 0.5f, fy = floorf(y), ty = y - fy;
    long j = (long)fy;
    uint32_t y0 = (uint32_t)(j < 0 ? 0 : (j >= (long)h ? (long)h - 1 : j));
    uint32_t y1 = (uint32_t)(j + 1 < 0 ? 0 : (j + 1 >= (long)h ? (long)h - 1 : j + 1));
    const float *t = sc->env_texels;
    uint64_t r0 = (uint64_t)y0 * w, r1 = (uint64_t)y1 * w;
    ilk_vec3 top = ilk_add(ilk_scale(ilk_texel(t, r0 + x0), 1.0f - tx), ilk_scale(ilk_texel(t, r0 + x1), tx));
    ilk_vec3 bot = ilk_add(ilk_scale(ilk_texel(t, r1 + x0), 1.0f - tx), ilk_scale(ilk_texel(t, r1 + x1), tx));
    return ilk_add(ilk_scale(top, 1.0f - ty), ilk_scale(bot, ty));
}

/* The bin of a piecewise-constant density that u falls in, by its CDF
 * (n + 1 entries): returns it, its probability in *pmf and u rescaled to
 * [0, 1) within it in *u_in (core/sampling.c's il_distrib1d_sample_discrete). */
IL_DEVICE_INLINE uint32_t ilk_cdf_sample(const float *cdf, uint32_t n, float u, float *pmf, float *u_in)
{
    uint32_t i = ilk_pick_light(cdf, n, u);
    float w = cdf[i + 1] - cdf[i];
    *pmf = w;
    float r = w > 0.0f ? (u - cdf[i]) / w : 0.0f;
    *u_in = ilk_minf(ilk_maxf(r, 0.0f), 0.99999994f);
    return i;
}

/* The radiance of the discs that direction d points into (scene/lights.c's
 * il_background_radiance less the environment). */
IL_DEVICE_INLINE ilk_vec3 ilk_discs(const ilk_scene *sc, ilk_vec3 d)
{
    ilk_vec3 L = ilk_v3(0, 0, 0);
    for (uint32_t i = 0; i < sc->num_discs; i++) {
        const ilk_disc *c = &sc->discs[i];
        ilk_vec3 x = ilk_cross(d, c->towards);
        if (ilk_dot(d, c->towards) > 0.0f && ilk_dot(x, x) <= c->sin2_radius)
            L = ilk_add(L, c->radiance);
    }
    return L;
}

/* Row j's conditional CDF in the map's sampling table (env_cdf). */
IL_DEVICE_INLINE const float *ilk_environment_row_cdf(const ilk_scene *sc, uint32_t j)
{
    return sc->env_cdf + (sc->env_grid_h + 1) + (uint64_t)j * (sc->env_grid_w + 1);
}

/* A world direction towards the map for (u1, u2), with its solid-angle
 * density (0: do not use it): a cell of the map's table by its marginal
 * and conditional CDFs, a point uniform in (u, v) inside it, and
 *   pdf = pmf(row) pmf(column) W H / (2 pi^2 sin theta)
 * (pbrt-v4 12.5.2; image/envmap_sample.c's il_envmap_sample).  Only for a
 * scene with a map (env_cdf). */
IL_DEVICE_INLINE float ilk_environment_sample(const ilk_scene *sc, float u1, float u2, ilk_vec3 *dir)
{
    uint32_t W = sc->env_grid_w, H = sc->env_grid_h;
    float pm, pc, um, uc;
    uint32_t j = ilk_cdf_sample(sc->env_cdf, H, u2, &pm, &um);
    uint32_t i = ilk_cdf_sample(ilk_environment_row_cdf(sc, j), W, u1, &pc, &uc);
    float fu = ((float)i + uc) / (float)W, fv = ((float)j + um) / (float)H;
    /* image/envmap.h's il_envmap_latlong_dir, then the map's turn to world. */
    float theta = ILK_PI * fv, phi = 2.0f * ILK_PI * (fu - 0.5f), st = sinf(theta);
    ilk_vec3 l = ilk_v3(st * sinf(phi), cosf(theta), -st * cosf(phi));
    float c = sc->env_cos_rot, s = sc->env_sin_rot;
    *dir = ilk_v3(l.x * c + l.z * s, l.y, -l.x * s + l.z * c);
    float p = pm * pc * (float)W * (float)H / (2.0f * ILK_PI * ILK_PI * st);
    return st > 0.0f && p > 0.0f && p < INFINITY ? p : 0.0f;
}

/* The solid-angle density with which ilk_environment_sample picks world
 * direction d (unit), as il_envmap_pdf.  Only for a scene with a map. */
IL_DEVICE_INLINE float ilk_environment_pdf(const ilk_scene *sc, ilk_vec3 d)
{
    float u, v, st;
    ilk_environment_uv(sc, d, &u, &v, &st);
    if (!(st > 0.0f))
        return 0.0f;
    uint32_t W = sc->env_grid_w, H = sc->env_grid_h;
    uint32_t i = (uint32_t)ilk_minf(u * (float)W, (float)(W - 1));
    uint32_t j = (uint32_t)ilk_minf(v * (float)H, (float)(H - 1));
    const float *row = ilk_environment_row_cdf(sc, j);
    float pm = sc->env_cdf[j + 1] - sc->env_cdf[j], pc = row[i + 1] - row[i];
    return pm * pc * (float)W * (float)H / (2.0f * ILK_PI * ILK_PI * st);
}

/* The power heuristic with exponent 2 (Veach 1997, 9.2.4): the weight of
 * a sample drawn with density a where the other strategy has density b. */
IL_DEVICE_INLINE float ilk_power_heuristic(float a, float b)
{
    float a2 = a * a, b2 = b * b;
    return a2 + b2 > 0.0f ? a2 / (a2 + b2) : 0.0f;
}

/* The texture at (u, v): bilinear, wrapping, v = 0 the bottom row, as
 * scene/scene.c's il_texture_sample. */
IL_DEVICE_INLINE ilk_vec3 ilk_texture_sample(const ilk_scene *sc, const ilk_texture *t, float u, float v)
{
    float x = (u - floorf(u)) * (float)t->width - 0.5f;
    float y = (1.0f - (v - floorf(v))) * (float)t->height - 0.5f;
    float fx = floorf(x), fy = floorf(y), tx = x - fx, ty = y - fy;
    int x0 = (int)fx, y0 = (int)fy, w = (int)t->width, h = (int)t->height;
    ilk_vec3 acc = ilk_v3(0, 0, 0);
    for (int j = 0; j < 2; j++)
        for (int i = 0; i < 2; i++) {
            int xi = ((x0 + i) % w + w) % w, yi = ((y0 + j) % h + h) % h;
            float wt = (i ? tx : 1.0f - tx) * (j ? ty : 1.0f - ty);
            acc = ilk_add(acc, ilk_scale(ilk_texel(sc->texels + t->offset, (uint64_t)yi * t->width + xi), wt));
        }
    return acc;
}

/* A textured material at barycentrics (b1, b2) of tris[tri], resolved as
 * il_bsdf_init does: kd = max(colour x texel, 0), and for Phong kd + ks
 * scaled down together to at most 1 per channel (Lafortune & Willems 1994,
 * section 3) and the diffuse lobe's probability by the albedos' luminance. */
IL_DEVICE_INLINE ilk_material ilk_material_at(const ilk_scene *sc, const ilk_material *m, uint32_t tri, float b1,
                                              float b2)
{
    ilk_material r = *m;
    const ilk_tri_uvs *tu = &sc->uvs[tri];
    float b0 = 1.0f - b1 - b2;
    float u = tu->u[0] * b0 + tu->u[1] * b1 + tu->u[2] * b2, v = tu->v[0] * b0 + tu->v[1] * b1 + tu->v[2] * b2;
    ilk_vec3 kd = ilk_mul(m->diffuse, ilk_texture_sample(sc, &sc->textures[m->texture - 1], u, v));
    kd = ilk_v3(ilk_maxf(kd.x, 0.0f), ilk_maxf(kd.y, 0.0f), ilk_maxf(kd.z, 0.0f));
    if (m->type == ILK_MATERIAL_PHONG) {
        ilk_vec3 ks = m->specular;
        float peak = ilk_max3(ilk_add(kd, ks));
        if (peak > 1.0f) {
            kd = ilk_scale(kd, 1.0f / peak);
            ks = ilk_scale(ks, 1.0f / peak);
        }
        float ld = ilk_luminance(kd), ls = ilk_luminance(ks);
        r.diffuse_prob = ld + ls > 0.0f ? ld / (ld + ls) : 1.0f;
        r.specular = ks;
    }
    r.diffuse = kd;
    r.texture = 0;
    return r;
}

/* p moved off its surface (geometric normal ng) to the side of dir, by the
 * tracer's epsilon grown with the coordinates' magnitude, as
 * il_offset_origin (float spacing grows with it). */
IL_DEVICE_INLINE ilk_vec3 ilk_offset(const ilk_scene *sc, ilk_vec3 p, ilk_vec3 ng, ilk_vec3 dir)
{
    float mag = ilk_maxf(fabsf(p.x), ilk_maxf(fabsf(p.y), fabsf(p.z)));
    float eps = sc->epsilon + mag * 4.0f * 1.1920929e-7f;
    return ilk_add(p, ilk_scale(ng, ilk_dot(ng, dir) >= 0.0f ? eps : -eps));
}

/* Next-event estimation at p (BSDF b, outgoing wo): one light of the path
 * table by power (u), for an area light one uniform point on its triangle
 * (u1, u2; pbrt-v4 section 6.5), and a shadow ray.  Returns
 * f Li |cos theta_i| / pdf, where for an area light Li = Le and pdf is the
 * choice probability times the solid-angle density
 * d^2 / (A |cos theta_l|) (pbrt-v4 equation 4.9), and for a delta light
 * (scene/lights.c, pbrt-v4 12.1-12.4) Li = I / d^2 (times the spot's
 * cos^n profile inside its cut-off) or the directional irradiance E, and
 * pdf is the choice probability.  For the environment, one direction
 * (u1, u2) by ilk_environment_sample, Li its radiance, pdf the choice
 * probability times the direction's density.  With `mis` (the path
 * kernel, whose BSDF-sampled rays find area lights and the environment
 * too) those two are weighted by the power heuristic against the BSDF's
 * density of the direction; without (the photon gather) they count whole.
 * *rays counts the shadow ray. */
IL_DEVICE_INLINE ilk_vec3 ilk_direct(const ilk_scene *sc, const ilk_bsdf *b, ilk_vec3 p, ilk_vec3 wo, float u,
                                     float u1, float u2, bool mis, uint32_t *rays)
{
    ilk_vec3 zero = ilk_v3(0, 0, 0);
    if (sc->num_pt_lights == 0)
        return zero;
    uint32_t li = ilk_pick_light(sc->pt_light_cdf, sc->num_pt_lights, u);
    float pmf = sc->pt_light_cdf[li + 1] - sc->pt_light_cdf[li];
    if (!(pmf > 0.0f))
        return zero;
    const ilk_light *l = &sc->pt_lights[li];
    ilk_vec3 wi, Li, target, target_n = zero;
    float pdf = pmf, dist = INFINITY;
    if (l->kind == ILK_LIGHT_DIRECTIONAL) {
        wi = ilk_scale(l->direction, -1.0f);
        Li = l->intensity;
        target = zero;
        if (l->cos_cutoff < 1.0f) {
            /* Across the light's disc, as il_directional_sample (scene/lights.c). */
            float omc = u1 * (1.0f - l->cos_cutoff), c = 1.0f - omc;
            float s = sqrtf(ilk_maxf(0.0f, omc * (2.0f - omc))), phi = 2.0f * ILK_PI * u2;
            wi = ilk_normalize(ilk_from_local(wi, s * cosf(phi), s * sinf(phi), c));
            Li = ilk_scale(Li, 2.0f / (1.0f + l->cos_cutoff));
        }
    } else if (l->kind == ILK_LIGHT_ENVIRONMENT) {
        pdf = pmf * ilk_environment_sample(sc, u1, u2, &wi);
        if (!(pdf > 0.0f))
            return zero;
        Li = ilk_environment(sc, wi);
        target = zero;
    } else {
        if (l->kind == ILK_LIGHT_AREA) {
            const ilk_tri *lt = &sc->bvh.tris[l->tri];
            float su = sqrtf(u1), lb2 = u2 * su, lb1 = su - lb2;
            target = ilk_add(lt->v0, ilk_add(ilk_scale(lt->e1, lb1), ilk_scale(lt->e2, lb2)));
            ilk_vec3 unused;
            ilk_surface_normals(sc, l->tri, lb1, lb2, &target_n, &unused);
        } else {
            target = l->position;
        }
        ilk_vec3 d = ilk_sub(target, p);
        float dist2 = ilk_dot(d, d);
        if (!(dist2 > 0.0f))
            return zero;
        dist = sqrtf(dist2);
        wi = ilk_scale(d, 1.0f / dist);
        if (l->kind == ILK_LIGHT_AREA) {
            const ilk_tri *lt = &sc->bvh.tris[l->tri];
            const ilk_material *lm = &sc->materials[lt->pad];
            float area = ilk_tri_area(lt), cos_l = ilk_dot(target_n, wi);
            if (!lm->two_sided && !(cos_l < 0.0f))
                return zero;                   /* the back of a one-sided emitter */
            cos_l = fabsf(cos_l);
            if (!(cos_l > 0.0f) || !(area > 0.0f))
                return zero;
            pdf = pmf * dist2 / (area * cos_l);
            Li = lm->emission;
        } else {
            float scale = 1.0f / dist2;
            if (l->kind == ILK_LIGHT_SPOT) {
                float c = -ilk_dot(l->direction, wi);
                if (c < l->cos_cutoff)
                    return zero;
                if (l->spot_exponent > 0.0f) {
                    if (c <= 0.0f)
                        return zero;
                    scale *= powf(c, l->spot_exponent);
                }
            }
            Li = ilk_scale(l->intensity, scale);
        }
    }
    if (!(pdf > 0.0f) || !(pdf < INFINITY) || !ilk_sides_agree(b, wo, wi))
        return zero;
    float bsdf_pdf;
    ilk_vec3 f = ilk_bsdf_eval(b, wo, wi, &bsdf_pdf);
    float cos_i = fabsf(ilk_dot(wi, b->ns));
    if (!(cos_i > 0.0f) || (f.x <= 0.0f && f.y <= 0.0f && f.z <= 0.0f))
        return zero;
    /* What the light gives unless the shadow ray is blocked, made before
     * the ray so that only it stays live through the traversal (fewer GPU
     * registers). */
    bool weighted = mis && (l->kind == ILK_LIGHT_ENVIRONMENT || l->kind == ILK_LIGHT_AREA);
    float w = weighted ? ilk_power_heuristic(pdf, bsdf_pdf) : 1.0f;
    ilk_vec3 contribution = ilk_scale(ilk_mul(f, Li), w * cos_i / pdf);
    /* The shadow ray, offset at both ends as il_shadow_ray (an area
     * light's end off its surface; a point light's is a point in space). */
    ilk_ray shadow;
    shadow.org = ilk_offset(sc, p, b->ng, wi);
    shadow.tmin = 0.0f;
    if (dist < INFINITY) {
        ilk_vec3 end = l->kind == ILK_LIGHT_AREA ? ilk_offset(sc, target, target_n, ilk_scale(wi, -1.0f)) : target;
        shadow.dir = ilk_sub(end, shadow.org);
        shadow.tmax = 1.0f - 1e-4f;
    } else {
        shadow.dir = wi;
        shadow.tmax = INFINITY;
    }
    ++*rays;
    if (ilk_bvh_occluded(&sc->bvh, &shadow))
        return zero;
    return contribution;
}

/* The pinhole camera ray through film position (x + u, y + v), as
 * scene/camera.c (pixel (0, 0) at the top left). */
IL_DEVICE_INLINE ilk_ray ilk_camera_ray(const ilk_camera *cam, uint32_t x, uint32_t y, float u, float v)
{
    float fx = (float)x + u, fy = (float)y + v;
    float sx = (2.0f * fx * cam->inv_width - 1.0f) * cam->tan_half_x;
    float sy = (1.0f - 2.0f * fy * cam->inv_height) * cam->tan_half_y;
    ilk_ray ray;
    ray.org = cam->position;
    ray.dir = ilk_normalize(ilk_add(cam->forward, ilk_add(ilk_scale(cam->right, sx), ilk_scale(cam->up, sy))));
    ray.tmin = 0.0f;
    ray.tmax = INFINITY;
    return ray;
}

/* The radiance of one camera sample through pixel (x, y).  `depth` counts
 * the scattering events before the current ray; max_depth bounds them as
 * the CPU's max_depth does (after the last one only what its BSDF-sampled
 * ray finds is counted: here the environment).  The rays it casts are
 * added to *rays. */
IL_DEVICE_INLINE ilk_vec3 ilk_path_sample(const ilk_scene *sc, uint32_t x, uint32_t y, uint32_t sample,
                                          uint32_t *rays)
{
    ilk_sobol smp = ilk_sobol_start(sc->seed, (uint64_t)y * sc->width + x, sample);
    float u, v;
    ilk_sobol_2d(&smp, &u, &v);
    ilk_ray ray = ilk_camera_ray(&sc->camera, x, y, u, v);
    ilk_vec3 L = ilk_v3(0, 0, 0), beta = ilk_v3(1, 1, 1);
    /* counts_emission: no NEE at the last vertex (camera rays, mirror or
     * glass bounces), so what the ray finds counts whole.  bsdf_pdf: the
     * density of the last bounce's direction, for the MIS weights. */
    bool counts_emission = true;
    bool camera_chain = true;      /* only mirror and glass bounces so far: the sun's disc shows */
    float bsdf_pdf = 0.0f;
    for (uint32_t depth = 0;; depth++) {
        ilk_hit h;
        ++*rays;
        if (!ilk_bvh_closest(&sc->bvh, &ray, &h)) {
            if (sc->has_environment) {
                /* After a non-delta bounce NEE could have picked this
                 * direction too: the power heuristic's BSDF-side weight. */
                float mis = 1.0f;
                if (!counts_emission && sc->env_light_pmf > 0.0f)
                    mis = ilk_power_heuristic(bsdf_pdf, sc->env_light_pmf * ilk_environment_pdf(sc, ray.dir));
                L = ilk_add(L, ilk_scale(ilk_mul(beta, ilk_environment(sc, ray.dir)), mis));
            }
            if (camera_chain)
                L = ilk_add(L, ilk_mul(beta, ilk_discs(sc, ray.dir)));
            break;
        }
        const ilk_tri *tr = &sc->bvh.tris[h.tri];
        ilk_bsdf b;
        b.m = &sc->materials[tr->pad];
        ilk_material textured;
        if (b.m->texture) {
            textured = ilk_material_at(sc, b.m, h.tri, h.b1, h.b2);
            b.m = &textured;
        }
        ilk_surface_normals(sc, h.tri, h.b1, h.b2, &b.ng, &b.ns);
        ilk_vec3 wo = ilk_scale(ray.dir, -1.0f);
        if ((ilk_dot(b.ng, wo) > 0.0f || b.m->two_sided) &&
            (b.m->emission.x > 0.0f || b.m->emission.y > 0.0f || b.m->emission.z > 0.0f)) {
            float mis = 1.0f;
            if (!counts_emission) {
                /* NEE could have picked this point: its solid-angle
                 * density pmf d^2 / (A |cos theta_l|) against the bounce's. */
                float area = ilk_tri_area(tr), cos_l = fabsf(ilk_dot(b.ng, wo));
                float light_pdf = sc->tri_light_pmf[h.tri] * h.t * h.t / (area * cos_l);
                mis = ilk_power_heuristic(bsdf_pdf, light_pdf);
            }
            L = ilk_add(L, ilk_scale(ilk_mul(beta, b.m->emission), mis));
        }
        if (depth >= sc->max_depth)
            break;
        ilk_vec3 p = ilk_add(ray.org, ilk_scale(ray.dir, h.t));
        bool delta = ilk_bsdf_is_delta(b.m);
        float ul, u_lobe, u1, u2;
        ilk_sobol_2d(&smp, &ul, &u_lobe);
        ilk_sobol_2d(&smp, &u1, &u2);
        if (!delta)
            L = ilk_add(L, ilk_mul(beta, ilk_direct(sc, &b, p, wo, ul, u1, u2, true, rays)));
        /* The last bounce only matters when what it finds is counted: the
         * sky, an emitter (MIS), or one seen through a mirror or glass. */
        if (depth + 1 >= sc->max_depth && !sc->has_environment && !sc->tri_light_pmf && !delta)
            break;
        ilk_sobol_2d(&smp, &u1, &u2);
        ilk_vec3 wi, weight;
        if (!ilk_bsdf_sample(&b, wo, u_lobe, u1, u2, &wi, &weight, &bsdf_pdf) || !ilk_sides_agree(&b, wo, wi))
            break;
        beta = ilk_mul(beta, weight);
        counts_emission = delta;
        camera_chain = camera_chain && delta;
        if (!(beta.x > 0.0f || beta.y > 0.0f || beta.z > 0.0f))
            break;
        /* Russian roulette after the third vertex, as the CPU path tracer
         * (pbrt-v4 13.4.4): go on with probability q = min(max component
         * of the throughput, 0.95) and divide by q, which keeps the
         * estimate unbiased. */
        if (depth >= 3) {
            float q = ilk_minf(ilk_max3(beta), 0.95f);
            float u_rr, u_unused;
            ilk_sobol_2d(&smp, &u_rr, &u_unused);
            if (!(u_rr < q))
                break;
            beta = ilk_scale(beta, 1.0f / q);
        }
        ray.dir = wi;
        ray.org = ilk_offset(sc, p, b.ng, wi);
        ray.tmin = 0.0f;
        ray.tmax = INFINITY;
    }
    return L;
}

#endif
