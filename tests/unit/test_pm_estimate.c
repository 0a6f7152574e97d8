/* Radiance estimates (src/methods/photon/pm_estimate.c): photons spread
 * uniformly over a large Lambertian plane, total power P over area A, give
 * the analytic radiance rho/pi * P/A with both filters (their
 * normalisations, Jensen 2001 7.2.2) and both structures; photons on a
 * perpendicular wall at a corner, on the back of a thin wall, or arriving
 * from below the surface, or on a parallel surface just under it add
 * nothing, while those on a facet or a sphere next to the query count; a fixed-radius estimate is the same
 * on a kd-tree and on a grid; an empty map gives zero; the Lambertian
 * shortcut (one product with rho/pi) equals the general per-photon BSDF
 * loop, including photons from below and bent shading normals. */
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "core/sampling.h"
#include "methods/photon/pm_internal.h"

#define SIDE 400               /* photons per side of the jittered grid */
#define HALF 2.0f              /* the plane is [-HALF, HALF]^2 at z = 0 */

static il_material g_mat;

static il_bsdf lambert(il_vec3 rho, il_vec3 n)
{
    memset(&g_mat, 0, sizeof g_mat);
    g_mat.type = IL_MATERIAL_DIFFUSE;
    g_mat.diffuse = rho;
    il_surface s = {0};
    s.ns = s.ng = n;
    s.material = &g_mat;
    il_bsdf b;
    il_bsdf_init(&b, NULL, &s);
    return b;
}

static il_vec3 upper_dir(il_pcg32 *r, il_vec3 n)
{
    il_frame f = il_frame_from_normal(n);
    float u = il_pcg32_float(r), phi = 2.0f * IL_PI * il_pcg32_float(r);
    float s = sqrtf(u);
    return il_frame_to_world(&f, v3(s * cosf(phi), s * sinf(phi), sqrtf(1.0f - u)));
}

/* SIDE^2 photons, one jittered in each cell of a grid over the floor (a
 * density uniform down to the cell), each of power `power` (unscaled),
 * then `extra` more from `add`. */
typedef void (*add_fn)(il_photon *out, size_t n, il_pcg32 *r);

static il_photon *floor_photons(size_t extra, add_fn add, size_t *count, uint64_t seed)
{
    size_t n = (size_t)SIDE * SIDE;
    il_photon *a = malloc((n + extra) * sizeof *a);
    il_pcg32 r = il_pcg32_seed(seed, 3);
    const float cell = 2.0f * HALF / SIDE;
    for (int j = 0; j < SIDE; j++)
        for (int i = 0; i < SIDE; i++) {
            il_vec3 p = v3(-HALF + cell * ((float)i + il_pcg32_float(&r)),
                           -HALF + cell * ((float)j + il_pcg32_float(&r)), 0.0f);
            a[(size_t)j * SIDE + i] = il_photon_pack(p, v3(1.0f, 0.5f, 0.25f), upper_dir(&r, v3(0, 0, 1)),
                                                     v3(0, 0, 1));
        }
    if (extra)
        add(a + n, extra, &r);
    *count = n + extra;
    return a;
}

/* A bright wall x = 0, z in [0, 1], facing +x: a corner with the floor. */
static void add_wall(il_photon *out, size_t n, il_pcg32 *r)
{
    for (size_t i = 0; i < n; i++) {
        il_vec3 p = v3(0.0f, HALF * (2.0f * il_pcg32_float(r) - 1.0f), il_pcg32_float(r));
        out[i] = il_photon_pack(p, v3s(1000.0f), upper_dir(r, v3(1, 0, 0)), v3(1, 0, 0));
    }
}
/* The back of a thin floor: same plane, facing down. */
static void add_back(il_photon *out, size_t n, il_pcg32 *r)
{
    for (size_t i = 0; i < n; i++) {
        il_vec3 p = v3(HALF * (2.0f * il_pcg32_float(r) - 1.0f), HALF * (2.0f * il_pcg32_float(r) - 1.0f), 0.0f);
        out[i] = il_photon_pack(p, v3s(1000.0f), upper_dir(r, v3(0, 0, -1)), v3(0, 0, -1));
    }
}
/* The ground 1 cm under the floor, facing up as the floor does (a floor
 * inside a wall without thickness, the ground outside it): rejected by the
 * disc, 1 cm being more than IL_PM_DISC_THICKNESS of either search's
 * radius here (grid 0.05; the kd-tree's 100 nearest lie within about 0.05). */
static void add_under(il_photon *out, size_t n, il_pcg32 *r)
{
    for (size_t i = 0; i < n; i++) {
        il_vec3 p = v3(HALF * (2.0f * il_pcg32_float(r) - 1.0f), HALF * (2.0f * il_pcg32_float(r) - 1.0f), -0.01f);
        out[i] = il_photon_pack(p, v3s(1000.0f), upper_dir(r, v3(0, 0, 1)), v3(0, 0, 1));
    }
}
/* Facing up but arriving from below (f = 0 for a reflective surface). */
static void add_below(il_photon *out, size_t n, il_pcg32 *r)
{
    for (size_t i = 0; i < n; i++) {
        il_vec3 p = v3(HALF * (2.0f * il_pcg32_float(r) - 1.0f), HALF * (2.0f * il_pcg32_float(r) - 1.0f), 0.0f);
        out[i] = il_photon_pack(p, v3s(1000.0f), upper_dir(r, v3(0, 0, -1)), v3(0, 0, 1));
    }
}

static il_pm_map build(il_photon *a, size_t n, float scale, il_photon_lookup lookup, float radius)
{
    il_pm_map m;
    il_error err;
    CHECK_OK(il_pm_map_build(&m, a, n, scale, lookup, radius, &err), &err);
    return m;
}

static il_vec3 estimate(const il_pm_map *m, il_pm_lookup q, const il_bsdf *b, il_vec3 p, il_vec3 wo,
                        il_pm_scratch *s)
{
    il_vec3 L = v3s(-1.0f);
    il_error err;
    CHECK_OK(il_pm_estimate(m, &q, b, p, v3(0, 0, 1), wo, s, &L, &err), &err);
    return L;
}

static void test_uniform_plane(void)
{
    const float P = 50.0f;                         /* watts, the red channel */
    const float A = (2.0f * HALF) * (2.0f * HALF);
    const il_vec3 rho = v3(0.8f, 0.5f, 0.3f);
    size_t n;
    il_photon *a = floor_photons(0, NULL, &n, 1);
    il_photon *b = malloc(n * sizeof *b);
    memcpy(b, a, n * sizeof *b);
    float scale = P / (float)n;                   /* photon power 1 -> P/n W */
    il_pm_map kd = build(a, n, scale, IL_PHOTON_KDTREE, 0.0f);
    il_pm_map grid = build(b, n, scale, IL_PHOTON_GRID, 0.06f);
    il_bsdf bsdf = lambert(rho, v3(0, 0, 1));
    il_vec3 wo = v3_normalize(v3(0.3f, -0.2f, 0.9f));
    /* rho/pi * E, E = P/A per channel (powers 1, 0.5, 0.25). */
    const il_vec3 expect = v3(rho.x * IL_INV_PI * P / A, rho.y * IL_INV_PI * 0.5f * P / A,
                              rho.z * IL_INV_PI * 0.25f * P / A);
    il_pm_scratch s = {0};
    il_pcg32 r = il_pcg32_seed(9, 9);
    const il_pm_lookup qs[4] = {
        {IL_PHOTON_KDTREE, 100, 0.2f, IL_PHOTON_CONE},
        {IL_PHOTON_KDTREE, 100, 0.2f, IL_PHOTON_EPANECHNIKOV},
        {IL_PHOTON_GRID, 0, 0.06f, IL_PHOTON_CONE},
        {IL_PHOTON_GRID, 0, 0.06f, IL_PHOTON_EPANECHNIKOV},
    };
    const int Q = 400;
    for (int v = 0; v < 4; v++) {
        const il_pm_map *m = qs[v].lookup == IL_PHOTON_KDTREE ? &kd : &grid;
        il_vec3 mean = v3s(0.0f);
        float worst = 0.0f;
        for (int i = 0; i < Q; i++) {
            il_vec3 p = v3(1.5f * (2.0f * il_pcg32_float(&r) - 1.0f), 1.5f * (2.0f * il_pcg32_float(&r) - 1.0f), 0.0f);
            il_vec3 L = estimate(m, qs[v], &bsdf, p, wo, &s);
            mean = v3_fma(mean, L, 1.0f / Q);
            worst = il_maxf(worst, fabsf(L.x / expect.x - 1.0f));
        }
        printf("filter %d: mean/expected %.4f %.4f %.4f, worst single %.3f\n", v, mean.x / expect.x,
               mean.y / expect.y, mean.z / expect.z, worst);
        CHECK_REL(mean.x, expect.x, 0.02);
        CHECK_REL(mean.y, expect.y, 0.02);
        CHECK_REL(mean.z, expect.z, 0.02);
        CHECK(worst < 0.10f);
    }
    /* A fixed-radius estimate on the kd-tree (k = 0) is the grid's. */
    for (int i = 0; i < 50; i++) {
        il_vec3 p = v3(2.0f * il_pcg32_float(&r) - 1.0f, 2.0f * il_pcg32_float(&r) - 1.0f, 0.0f);
        il_pm_lookup q = {IL_PHOTON_KDTREE, 0, 0.05f, (il_photon_filter)(i & 1)};
        il_vec3 Lk = estimate(&kd, q, &bsdf, p, wo, &s);
        q.lookup = IL_PHOTON_GRID;
        il_vec3 Lg = estimate(&grid, q, &bsdf, p, wo, &s);
        CHECK_REL(Lk.x, Lg.x, 1e-5);
        CHECK_REL(Lk.z, Lg.z, 1e-5);
        CHECK(Lk.x > 0.0f);
    }
    /* Below the surface (wo on the other side of the bsdf's normal): nothing. */
    il_vec3 L = estimate(&kd, qs[0], &bsdf, v3s(0.0f), v3(0, 0, -1), &s);
    CHECK(L.x == 0.0f && L.y == 0.0f && L.z == 0.0f);
    il_pm_scratch_free(&s);
    il_pm_map_free(&kd);
    il_pm_map_free(&grid);
}

/* Photons that must not count: at the query the estimate is the floor's
 * alone (grid: exactly; kd-tree: the wall takes k slots but adds nothing,
 * so it stays near the floor's value instead of 1000 times it). */
static void test_rejected(add_fn add, const char *what)
{
    size_t n, n0;
    il_photon *a = floor_photons(100000, add, &n, 2);
    il_photon *a0 = floor_photons(0, NULL, &n0, 2);  /* the same floor photons */
    il_photon *b = malloc(n * sizeof *b), *b0 = malloc(n0 * sizeof *b0);
    memcpy(b, a, n * sizeof *b);
    memcpy(b0, a0, n0 * sizeof *b0);
    il_pm_map kd = build(a, n, 1e-3f, IL_PHOTON_KDTREE, 0.0f);
    il_pm_map kd0 = build(a0, n0, 1e-3f, IL_PHOTON_KDTREE, 0.0f);
    il_pm_map grid = build(b, n, 1e-3f, IL_PHOTON_GRID, 0.05f);
    il_pm_map grid0 = build(b0, n0, 1e-3f, IL_PHOTON_GRID, 0.05f);
    il_bsdf bsdf = lambert(v3s(0.5f), v3(0, 0, 1));
    il_vec3 wo = v3_normalize(v3(0.5f, 0.1f, 0.8f));
    il_pm_scratch s = {0};
    bool grid_same = true, kd_near = true;
    for (int i = 0; i < 40; i++) {
        il_vec3 p = v3(0.005f + 0.002f * (float)i, -1.0f + 0.05f * (float)i, 0.0f);
        il_pm_lookup q = {IL_PHOTON_GRID, 0, 0.05f, (il_photon_filter)(i & 1)};
        il_vec3 Lg = estimate(&grid, q, &bsdf, p, wo, &s), Lg0 = estimate(&grid0, q, &bsdf, p, wo, &s);
        grid_same = grid_same && fabsf(Lg.x - Lg0.x) <= 1e-5f * Lg0.x && Lg0.x > 0.0f;
        q = (il_pm_lookup){IL_PHOTON_KDTREE, 100, 0.2f, (il_photon_filter)(i & 1)};
        il_vec3 Lk = estimate(&kd, q, &bsdf, p, wo, &s), Lk0 = estimate(&kd0, q, &bsdf, p, wo, &s);
        kd_near = kd_near && Lk.x <= 1.5f * Lk0.x && Lk.x >= 0.2f * Lk0.x;
    }
    if (!grid_same || !kd_near)
        fprintf(stderr, "photons %s were not rejected\n", what);
    CHECK(grid_same);
    CHECK(kd_near);
    il_pm_scratch_free(&s);
    il_pm_map_free(&kd);
    il_pm_map_free(&kd0);
    il_pm_map_free(&grid);
    il_pm_map_free(&grid0);
}

static void test_empty(void)
{
    il_bsdf bsdf = lambert(v3s(0.5f), v3(0, 0, 1));
    il_pm_scratch s = {0};
    for (int st = 0; st < 2; st++) {
        il_pm_map m = build(NULL, 0, 1.0f, st ? IL_PHOTON_GRID : IL_PHOTON_KDTREE, 0.1f);
        il_pm_lookup q = {st ? IL_PHOTON_GRID : IL_PHOTON_KDTREE, 50, 0.1f, IL_PHOTON_CONE};
        il_vec3 L = estimate(&m, q, &bsdf, v3s(0.0f), v3(0, 0, 1), &s);
        CHECK(L.x == 0.0f && L.y == 0.0f && L.z == 0.0f);
        il_pm_map_free(&m);
    }
    /* One photon exactly at the query with k = 1: r = 0, no estimate
     * rather than infinity. */
    il_photon *a = malloc(sizeof *a);
    a[0] = il_photon_pack(v3s(0.0f), v3s(1.0f), v3(0, 0, 1), v3(0, 0, 1));
    il_pm_map m = build(a, 1, 1.0f, IL_PHOTON_KDTREE, 0.0f);
    il_pm_lookup q = {IL_PHOTON_KDTREE, 1, 0.1f, IL_PHOTON_CONE};
    il_vec3 L = estimate(&m, q, &bsdf, v3s(0.0f), v3(0, 0, 1), &s);
    CHECK(isfinite(L.x) && L.x == 0.0f);
    /* Found fewer than k: r is the largest radius. */
    q.k = 5;
    L = estimate(&m, q, &bsdf, v3s(0.0f), v3(0, 0, 1), &s);
    CHECK_REL(L.x, 0.5f * IL_INV_PI * 1.0f / ((1.0f - 2.0f / 3.3f) * IL_PI * 0.01f), 1e-3);
    il_pm_map_free(&m);
    il_pm_scratch_free(&s);
}

/* A Phong BSDF without its specular lobe is Lambertian term for term
 * (f = kd/pi + 0), but il_pm_estimate evaluates it per photon; the diffuse
 * material takes the shortcut.  Both must agree up to float rounding, for
 * photons from every direction (half of them from below) and shading
 * normals bent away from the geometric one, wo on either side. */
static void test_lambert_shortcut(void)
{
    il_pcg32 r = il_pcg32_seed(11, 4);
    const size_t n = 20000;
    il_photon *a = malloc(n * sizeof *a);
    for (size_t i = 0; i < n; i++) {
        il_vec3 p = v3(2.0f * il_pcg32_float(&r) - 1.0f, 2.0f * il_pcg32_float(&r) - 1.0f, 0.0f);
        il_vec3 d = il_sample_uniform_sphere(v2(il_pcg32_float(&r), il_pcg32_float(&r)));
        a[i] = il_photon_pack(p, v3(il_pcg32_float(&r), 0.5f, 2.0f), d, v3(0, 0, 1));
    }
    il_pm_map kd = build(a, n, 0.01f, IL_PHOTON_KDTREE, 0.0f);
    il_pm_scratch s = {0};
    il_material diffuse = {0}, phong = {0};
    diffuse.type = IL_MATERIAL_DIFFUSE;
    diffuse.diffuse = phong.diffuse = v3(0.7f, 0.4f, 0.2f);
    phong.type = IL_MATERIAL_PHONG;
    phong.exponent = 20.0f;
    int compared = 0, nonzero = 0;
    for (int i = 0; i < 200; i++) {
        il_surface sf = {0};
        sf.ng = v3(0, 0, 1);
        /* shading normal tilted up to ~35 degrees */
        sf.ns = v3_normalize(v3(0.7f * (il_pcg32_float(&r) - 0.5f), 0.7f * (il_pcg32_float(&r) - 0.5f), 1.0f));
        il_vec3 wo = il_sample_uniform_sphere(v2(il_pcg32_float(&r), il_pcg32_float(&r)));
        il_vec3 p = v3(1.6f * il_pcg32_float(&r) - 0.8f, 1.6f * il_pcg32_float(&r) - 0.8f, 0.0f);
        il_vec3 nq = wo.z < 0.0f ? v3(0, 0, -1) : v3(0, 0, 1);
        il_pm_lookup q = {IL_PHOTON_KDTREE, 50, 0.3f, (il_photon_filter)(i & 1)};
        il_bsdf bd, bp;
        sf.material = &diffuse;
        il_bsdf_init(&bd, NULL, &sf);
        sf.material = &phong;
        il_bsdf_init(&bp, NULL, &sf);
        il_vec3 Ld, Lp;
        il_error err;
        CHECK_OK(il_pm_estimate(&kd, &q, &bd, p, nq, wo, &s, &Ld, &err), &err);
        CHECK_OK(il_pm_estimate(&kd, &q, &bp, p, nq, wo, &s, &Lp, &err), &err);
        CHECK(fabsf(Ld.x - Lp.x) <= 1e-5f * Lp.x && fabsf(Ld.z - Lp.z) <= 1e-5f * Lp.z);
        compared++;
        nonzero += Lp.x > 0.0f;
    }
    printf("lambert shortcut: %d compared, %d nonzero\n", compared, nonzero);
    CHECK(nonzero > 50);
    il_pm_scratch_free(&s);
    il_pm_map_free(&kd);
}

/* The estimates' normal test without normalising (pm_internal.h) is the
 * normalised one for every 14-bit normal code, away from float ties. */
static void test_normal_test(void)
{
    il_pcg32 r = il_pcg32_seed(12, 1);
    int differ = 0, agree = 0;
    for (int t = 0; t < 40; t++) {
        il_vec3 n = il_sample_uniform_sphere(v2(il_pcg32_float(&r), il_pcg32_float(&r)));
        for (uint32_t code = 0; code < (1u << 14); code++) {
            il_photon ph = {0};
            ph.normal = (uint16_t)code;
            float d = v3_dot(il_photon_normal(&ph), n);
            bool fast = il_pm_normal_agrees(&ph, n);
            agree += fast;
            if (fabsf(d - IL_PM_NORMAL_COS) > 1e-5f && fast != (d >= IL_PM_NORMAL_COS))
                differ++;
        }
    }
    printf("normal test: %d codes agree, %d differ from the normalised test\n", agree, differ);
    CHECK(differ == 0);
    CHECK(agree > 1000);
}

/* il_pm_on_surface against the query x = 0 with normal +z and a search
 * radius r: photons on the query's plane count at any distance; on a
 * parallel plane they count only within IL_PM_DISC_THICKNESS * r of it;
 * photons on a plane through a point of the query's plane, turned by up to
 * the normal test's 25.8 degrees (a tessellated curve's next facet), and on
 * a sphere touching the plane at x (a smooth curve), count out to r. */
static void test_on_surface(void)
{
    const float r = 0.2f;
    il_vec3 n = v3(0, 0, 1), x = v3s(0.0f);
    il_pcg32 rng = il_pcg32_seed(13, 1);
    int wrong = 0;
    for (int i = 0; i < 2000; i++) {
        float phi = 2.0f * IL_PI * il_pcg32_float(&rng), d = r * sqrtf(il_pcg32_float(&rng));
        il_vec3 u = v3(cosf(phi), sinf(phi), 0.0f);
        il_photon flat = il_photon_pack(v3_scale(u, d), v3s(1.0f), n, n);
        il_photon near = il_photon_pack(v3(u.x * d, u.y * d, -0.05f * r), v3s(1.0f), n, n);
        il_photon far = il_photon_pack(v3(u.x * d, u.y * d, -0.2f * r), v3s(1.0f), n, n);
        wrong += !il_pm_on_surface(&flat, n, x, r) + !il_pm_on_surface(&near, n, x, r) +
                 il_pm_on_surface(&far, n, x, r);
        /* a facet turned by theta about the axis perpendicular to u, through
         * a point a of the query's plane on u's line (|a| < d) */
        float theta = 0.45f * il_pcg32_float(&rng), a = d * il_pcg32_float(&rng);
        il_vec3 along = v3(u.x * cosf(theta), u.y * cosf(theta), sinf(theta));
        il_vec3 fn = v3(-u.x * sinf(theta), -u.y * sinf(theta), cosf(theta));
        il_vec3 q = v3_add(v3_scale(u, a), v3_scale(along, d - a));
        il_photon facet = il_photon_pack(q, v3s(1.0f), fn, fn);
        /* a sphere of radius R on the plane at x, the photon at arc length d */
        float t = fmaxf(theta, 1e-3f), R = d / t;
        il_vec3 sn = v3(-u.x * sinf(t), -u.y * sinf(t), cosf(t));
        il_photon ball = il_photon_pack(v3(u.x * R * sinf(t), u.y * R * sinf(t), R * (1.0f - cosf(t))), v3s(1.0f),
                                        sn, sn);
        if (v3_dot(il_photon_normal(&facet), n) > IL_PM_NORMAL_COS + 0.01f)
            wrong += !il_pm_on_surface(&facet, n, x, r);
        if (v3_dot(il_photon_normal(&ball), n) > IL_PM_NORMAL_COS + 0.01f)
            wrong += !il_pm_on_surface(&ball, n, x, r);
    }
    printf("disc test: %d of 10000 photons wrongly in or out\n", wrong);
    CHECK(wrong == 0);
}

int main(void)
{
    test_on_surface();
    test_normal_test();
    test_lambert_shortcut();
    test_uniform_plane();
    test_rejected(add_wall, "on a perpendicular wall");
    test_rejected(add_back, "on the back of a thin wall");
    test_rejected(add_below, "arriving from below");
    test_rejected(add_under, "on the ground just under the floor");
    test_empty();
    return check_report();
}
