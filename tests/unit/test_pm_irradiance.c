/* Precomputed irradiance (src/methods/photon/pm_irradiance.c, Christensen
 * 1999): on a uniform photon density over a Lambertian plane the lookup
 * gives the analytic radiance rho/pi * P/A and agrees with the full
 * estimate, with the kd-tree and with the grid; the points are the same for
 * 1 and 2 threads; at a corner the normal test picks the floor's points for
 * a floor query and the wall's for a wall query; nothing is found far away
 * or facing the other way; a Phong surface still gets the full estimate. */
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "methods/photon/pm.h"

#define HALF 2.0f              /* the floor is [-HALF, HALF]^2 at z = 0 */

static il_material g_mat[2];

static il_bsdf surface_bsdf(int slot, il_material_type type, il_vec3 rho, il_vec3 n)
{
    memset(&g_mat[slot], 0, sizeof g_mat[slot]);
    g_mat[slot].type = type;
    g_mat[slot].diffuse = rho;
    g_mat[slot].specular = v3s(0.3f);
    g_mat[slot].exponent = 10.0f;
    il_surface s = {0};
    s.ns = s.ng = n;
    s.material = &g_mat[slot];
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

/* nu x nv photons jittered over the rectangle o + [0,1]^2 (u, v), facing n. */
static size_t add_rect(il_photon *a, int nu, int nv, il_vec3 o, il_vec3 u, il_vec3 v, il_vec3 n,
                       il_vec3 power, il_pcg32 *r)
{
    size_t k = 0;
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            float s = ((float)i + il_pcg32_float(r)) / (float)nu;
            float t = ((float)j + il_pcg32_float(r)) / (float)nv;
            il_vec3 p = v3_add(o, v3_add(v3_scale(u, s), v3_scale(v, t)));
            a[k++] = il_photon_pack(p, power, upper_dir(r, n), n);
        }
    return k;
}

static il_pm_map build(il_photon *a, size_t n, float scale, const il_pm_lookup *q, int threads)
{
    il_pm_map m;
    il_error err;
    CHECK_OK(il_pm_map_build(&m, a, n, scale, q->lookup, q->radius, &err), &err);
    CHECK_OK(il_pm_irradiance_build(&m, q, IL_PM_IRRADIANCE_STRIDE, threads, &err), &err);
    return m;
}

static il_vec3 global(const il_pm_map *m, const il_pm_lookup *q, const il_bsdf *b, il_vec3 p,
                      il_vec3 n, il_vec3 wo, il_pm_scratch *s, bool full)
{
    il_vec3 L = v3s(-1.0f);
    il_error err;
    if (full)
        CHECK_OK(il_pm_estimate(m, q, b, p, n, wo, s, &L, &err), &err);
    else
        CHECK_OK(il_pm_estimate_global(m, q, b, p, n, wo, s, &L, &err), &err);
    return L;
}

static void test_uniform_plane(void)
{
    const int side = 300;
    const size_t n = (size_t)side * side;
    const float P = 40.0f, A = 4.0f * HALF * HALF;
    const il_vec3 rho = v3(0.8f, 0.5f, 0.3f);
    const il_vec3 expect = v3(rho.x * IL_INV_PI * P / A, rho.y * IL_INV_PI * 0.5f * P / A,
                              rho.z * IL_INV_PI * 0.25f * P / A);
    const il_pm_lookup qs[2] = {{IL_PHOTON_KDTREE, 100, 0.3f, IL_PHOTON_CONE},
                                {IL_PHOTON_GRID, 0, 0.08f, IL_PHOTON_EPANECHNIKOV}};
    il_bsdf bsdf = surface_bsdf(0, IL_MATERIAL_DIFFUSE, rho, v3(0, 0, 1));
    il_bsdf phong = surface_bsdf(1, IL_MATERIAL_PHONG, rho, v3(0, 0, 1));
    il_pm_scratch s = {0};
    for (int v = 0; v < 2; v++) {
        il_pcg32 r = il_pcg32_seed(5, 1);
        il_photon *a = malloc(n * sizeof *a), *b = malloc(n * sizeof *b);
        add_rect(a, side, side, v3(-HALF, -HALF, 0), v3(2 * HALF, 0, 0), v3(0, 2 * HALF, 0),
                 v3(0, 0, 1), v3(1.0f, 0.5f, 0.25f), &r);
        memcpy(b, a, n * sizeof *b);
        il_pm_map m1 = build(a, n, P / (float)n, &qs[v], 1);
        il_pm_map m2 = build(b, n, P / (float)n, &qs[v], 2);
        /* Every 4th photon, the same values whatever the thread count. */
        CHECK(m1.irr_count == (n + 3) / 4 && m2.irr_count == m1.irr_count);
        CHECK(m1.irr && m2.irr && memcmp(m1.irr, m2.irr, m1.irr_count * sizeof *m1.irr) == 0);

        il_vec3 mean = v3s(0.0f), mean_full = v3s(0.0f);
        float worst = 0.0f, worst_vs_full = 0.0f;
        const int Q = 300;
        il_pcg32 rq = il_pcg32_seed(8, 2);
        for (int i = 0; i < Q; i++) {
            il_vec3 p = v3(1.4f * (2.0f * il_pcg32_float(&rq) - 1.0f), 1.4f * (2.0f * il_pcg32_float(&rq) - 1.0f), 0.0f);
            il_vec3 wo = upper_dir(&rq, v3(0, 0, 1));
            il_vec3 L = global(&m1, &qs[v], &bsdf, p, v3(0, 0, 1), wo, &s, false);
            il_vec3 Lf = global(&m1, &qs[v], &bsdf, p, v3(0, 0, 1), wo, &s, true);
            mean = v3_fma(mean, L, 1.0f / Q);
            mean_full = v3_fma(mean_full, Lf, 1.0f / Q);
            worst = il_maxf(worst, fabsf(L.x / expect.x - 1.0f));
            worst_vs_full = il_maxf(worst_vs_full, fabsf(L.x / Lf.x - 1.0f));
            /* A Phong surface is not Lambertian: the full estimate. */
            il_vec3 Lp = global(&m1, &qs[v], &phong, p, v3(0, 0, 1), wo, &s, false);
            il_vec3 Lpf = global(&m1, &qs[v], &phong, p, v3(0, 0, 1), wo, &s, true);
            CHECK(Lp.x == Lpf.x && Lp.y == Lpf.y && Lp.z == Lpf.z);
        }
        printf("lookup %d: precomputed/expected %.4f %.4f %.4f, full/expected %.4f, worst %.3f, "
               "worst vs full %.3f\n",
               v, mean.x / expect.x, mean.y / expect.y, mean.z / expect.z, mean_full.x / expect.x,
               worst, worst_vs_full);
        CHECK_REL(mean.x, expect.x, 0.02);
        CHECK_REL(mean.y, expect.y, 0.02);
        CHECK_REL(mean.z, expect.z, 0.02);
        CHECK_REL(mean.x, mean_full.x, 0.02);
        CHECK(worst < 0.10f);
        CHECK(worst_vs_full < 0.10f);

        /* Far from the plane, or facing away from it: no point. */
        il_vec3 E;
        CHECK(!il_pm_irradiance_lookup(&m1, v3(0, 0, 1.0f), v3(0, 0, 1), qs[v].radius * qs[v].radius, &E));
        CHECK(E.x == 0.0f);
        CHECK(!il_pm_irradiance_lookup(&m1, v3(0.1f, 0.2f, 0), v3(0, 0, -1), qs[v].radius * qs[v].radius, &E));
        CHECK(il_pm_irradiance_lookup(&m1, v3(0.1f, 0.2f, 0), v3(0, 0, 1), qs[v].radius * qs[v].radius, &E));
        CHECK_REL(E.x, P / A, 0.10);
        il_pm_map_free(&m1);
        il_pm_map_free(&m2);
    }
    il_pm_scratch_free(&s);
}

/* A floor (z = 0, facing +z, photon power 1) meets a bright wall (x = 0,
 * z in [0, 1], facing +x, photon power 1000).  Floor queries beside the
 * wall get the floor's irradiance, wall queries the wall's: the nearest
 * point with an agreeing normal, not the nearest point. */
static void test_corner(void)
{
    const int fs = 300, wu = 300, wv = 75;
    const size_t n = (size_t)fs * fs + (size_t)wu * wv;
    il_pcg32 r = il_pcg32_seed(6, 6);
    il_photon *a = malloc(n * sizeof *a);
    size_t k = add_rect(a, fs, fs, v3(-HALF, -HALF, 0), v3(2 * HALF, 0, 0), v3(0, 2 * HALF, 0),
                        v3(0, 0, 1), v3s(1.0f), &r);
    k += add_rect(a + k, wu, wv, v3(0, -HALF, 0), v3(0, 2 * HALF, 0), v3(0, 0, 1), v3(1, 0, 0),
                  v3s(1000.0f), &r);
    CHECK(k == n);
    const float E_floor = (float)(fs * fs) / (4.0f * HALF * HALF);          /* scale 1 */
    const float E_wall = 1000.0f * (float)(wu * wv) / (2.0f * HALF * 1.0f);
    const il_pm_lookup q = {IL_PHOTON_KDTREE, 100, 0.3f, IL_PHOTON_CONE};
    il_pm_map m = build(a, n, 1.0f, &q, 2);
    bool floor_ok = true, wall_ok = true, corner_ok = true;
    for (int i = 0; i < 40; i++) {
        float y = -1.5f + 0.075f * (float)i;
        il_vec3 E;
        /* The floor right beside the wall. */
        bool f = il_pm_irradiance_lookup(&m, v3(0.004f + 0.001f * (float)(i % 5), y, 0.0f), v3(0, 0, 1),
                                         q.radius * q.radius, &E);
        floor_ok = floor_ok && f && E.x > 0.5f * E_floor && E.x < 1.5f * E_floor;
        /* The middle of the wall. */
        bool w = il_pm_irradiance_lookup(&m, v3(0.0f, y, 0.3f + 0.01f * (float)(i % 20)), v3(1, 0, 0),
                                         q.radius * q.radius, &E);
        wall_ok = wall_ok && w && fabsf(E.x / E_wall - 1.0f) < 0.10f;
        /* The very corner, as a wall point: the wall's side, not the floor's. */
        bool c = il_pm_irradiance_lookup(&m, v3(0.001f, y, 0.002f), v3(1, 0, 0), q.radius * q.radius, &E);
        corner_ok = corner_ok && c && E.x > 0.25f * E_wall;
    }
    printf("corner: floor %s, wall %s, corner %s (E_floor %.4g, E_wall %.4g)\n", floor_ok ? "ok" : "BAD",
           wall_ok ? "ok" : "BAD", corner_ok ? "ok" : "BAD", E_floor, E_wall);
    CHECK(floor_ok);
    CHECK(wall_ok);
    CHECK(corner_ok);
    il_pm_map_free(&m);
}

static void test_empty(void)
{
    il_pm_map m;
    il_error err;
    const il_pm_lookup q = {IL_PHOTON_KDTREE, 10, 0.1f, IL_PHOTON_CONE};
    CHECK_OK(il_pm_map_build(&m, NULL, 0, 1.0f, IL_PHOTON_KDTREE, 0.1f, &err), &err);
    CHECK_OK(il_pm_irradiance_build(&m, &q, 4, 1, &err), &err);
    CHECK(m.irr == NULL && m.irr_count == 0);
    il_vec3 E = v3s(1.0f);
    CHECK(!il_pm_irradiance_lookup(&m, v3s(0.0f), v3(0, 0, 1), 1.0f, &E));
    CHECK(E.x == 0.0f);
    il_pm_map_free(&m);
}

int main(void)
{
    test_uniform_plane();
    test_corner();
    test_empty();
    return check_report();
}
