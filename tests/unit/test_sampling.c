/* Sampling warps: every pdf integrates to 1 (quadrature), sample histograms
 * match the pdf (chi-square), triangle samples are uniform, discrete 1D
 * distributions sample in proportion to their weights. */
#include <string.h>

#include "check.h"
#include "chi2.h"
#include "core/rng.h"
#include "core/sampling.h"

#define PI_D 3.14159265358979323846
#define NUM_SAMPLES 100000
/* Chi-square tests in this program: 9 direction warps (2 each) + disk +
 * triangle + distrib1d. */
#define NUM_CHI2_TESTS 21
static double g_alpha;

/* ------------------------------------------------------- direction warps */

typedef struct warp {
    const char *name;
    int kind;       /* which warp */
    float param;    /* cone: cos_max; phong: exponent */
} warp;

enum { W_COSINE, W_HEMI, W_SPHERE, W_CONE, W_PHONG };

static il_vec3 warp_sample(const warp *w, il_vec2 u)
{
    switch (w->kind) {
    case W_COSINE: return il_sample_cosine_hemisphere(u);
    case W_HEMI: return il_sample_uniform_hemisphere(u);
    case W_SPHERE: return il_sample_uniform_sphere(u);
    case W_CONE: return il_sample_uniform_cone(u, w->param);
    default: return il_sample_phong_lobe(u, w->param);
    }
}

/* The solid-angle density, as the library states it. */
static double warp_pdf(const warp *w, double z)
{
    switch (w->kind) {
    case W_COSINE: return il_cosine_hemisphere_pdf((float)z);
    case W_HEMI: return z >= 0.0 ? 1.0 / (2.0 * PI_D) : 0.0;
    case W_SPHERE: return 1.0 / (4.0 * PI_D);
    case W_CONE: return z >= w->param ? il_uniform_cone_pdf(w->param) : 0.0;
    default: return il_phong_lobe_pdf((float)z, w->param);
    }
}

/* Integral of the (axially symmetric) pdf over z in [a, b], all phi:
 * 2 pi * composite Simpson in z (d omega = dz dphi).  Discontinuities (cone
 * edge, horizon) fall on cell edges below, so Simpson is accurate. */
static double warp_mass(const warp *w, double a, double b, int steps)
{
    double h = (b - a) / steps, s = 0.0;
    for (int i = 0; i <= steps; i++) {
        double z = a + i * h;
        /* Evaluate just inside the interval at the ends (pdfs may jump there). */
        if (i == 0) z = a + 1e-9;
        if (i == steps) z = b - 1e-9;
        double c = (i == 0 || i == steps) ? 1.0 : (i % 2 ? 4.0 : 2.0);
        s += c * warp_pdf(w, z);
    }
    return 2.0 * PI_D * s * h / 3.0;
}

static void test_warp_pdf_integrates_to_one(const warp *w)
{
    /* Split at 0 and at the cone edge so the integrand is smooth on each piece. */
    double total = 0.0;
    double edges[4] = {-1.0, 0.0, 1.0, 1.0};
    int ne = 3;
    if (w->kind == W_CONE) {
        edges[1] = fmin(0.0, w->param);
        edges[2] = fmax(0.0, w->param);
        edges[3] = 1.0;
        ne = 4;
    }
    for (int i = 0; i + 1 < ne; i++)
        total += warp_mass(w, edges[i], edges[i + 1], 20000);
    if (fabs(total - 1.0) > 1e-4)
        fprintf(stderr, "%s: pdf integrates to %.6f\n", w->name, total);
    CHECK_NEAR(total, 1.0, 1e-4);
}

static void test_warp_chi2(const warp *w, uint64_t seed)
{
    enum { NZ = 40, NPHI = 40 };
    static double obs[NZ * NPHI], expd[NZ * NPHI];
    memset(obs, 0, sizeof obs);
    il_pcg32 rng = il_pcg32_seed(seed, 7);
    int bad = 0;
    for (int i = 0; i < NUM_SAMPLES; i++) {
        il_vec2 u = v2(il_pcg32_float(&rng), il_pcg32_float(&rng));
        il_vec3 d = warp_sample(w, u);
        if (!(fabs(v3_length(d) - 1.0f) < 1e-4f)) {
            bad++;
            continue;
        }
        double phi = atan2(d.y, d.x);
        if (phi < 0.0) phi += 2.0 * PI_D;
        int iz = (int)((d.z + 1.0) * 0.5 * NZ), ip = (int)(phi / (2.0 * PI_D) * NPHI);
        iz = iz < 0 ? 0 : (iz >= NZ ? NZ - 1 : iz);
        ip = ip < 0 ? 0 : (ip >= NPHI ? NPHI - 1 : ip);
        obs[iz * NPHI + ip] += 1.0;
    }
    CHECK(bad == 0);
    for (int iz = 0; iz < NZ; iz++) {
        double a = -1.0 + 2.0 * iz / NZ, b = -1.0 + 2.0 * (iz + 1) / NZ;
        double m;
        if (w->kind == W_CONE && a < w->param && w->param < b)
            m = warp_mass(w, w->param, b, 512);   /* the cone edge inside this cell */
        else
            m = warp_mass(w, a, b, 512);
        for (int ip = 0; ip < NPHI; ip++)
            expd[iz * NPHI + ip] = m / NPHI * NUM_SAMPLES;
    }
    double p = chi2_pvalue(obs, expd, NZ * NPHI, w->name);
    if (!(p > g_alpha))
        fprintf(stderr, "%s: chi-square rejects the warp, p = %g < %g\n", w->name, p, g_alpha);
    CHECK(p > g_alpha);

    /* The marginal in z alone, finely binned: far more sensitive to a wrong
     * radial profile than the 2D histogram, which also tests phi. */
    enum { NZ1 = 200 };
    static double obs1[NZ1], expd1[NZ1];
    memset(obs1, 0, sizeof obs1);
    rng = il_pcg32_seed(seed, 8);
    for (int i = 0; i < NUM_SAMPLES; i++) {
        il_vec3 d = warp_sample(w, v2(il_pcg32_float(&rng), il_pcg32_float(&rng)));
        int iz = (int)((d.z + 1.0) * 0.5 * NZ1);
        obs1[iz < 0 ? 0 : (iz >= NZ1 ? NZ1 - 1 : iz)] += 1.0;
    }
    for (int iz = 0; iz < NZ1; iz++) {
        double a = -1.0 + 2.0 * iz / NZ1, b = -1.0 + 2.0 * (iz + 1) / NZ1;
        if (w->kind == W_CONE && a < w->param && w->param < b)
            a = w->param;
        expd1[iz] = warp_mass(w, a, b, 512) * NUM_SAMPLES;
    }
    char label[96];
    snprintf(label, sizeof label, "%s (z marginal)", w->name);
    p = chi2_pvalue(obs1, expd1, NZ1, label);
    if (!(p > g_alpha))
        fprintf(stderr, "%s: chi-square rejects the warp, p = %g < %g\n", label, p, g_alpha);
    CHECK(p > g_alpha);
}

/* ----------------------------------------------------------------- disk */

static void test_concentric_disk(void)
{
    /* Uniform on the unit disk: uniform in (r^2, phi). */
    enum { NR = 20, NPHI = 40 };
    static double obs[NR * NPHI], expd[NR * NPHI];
    memset(obs, 0, sizeof obs);
    il_pcg32 rng = il_pcg32_seed(11, 3);
    int outside = 0;
    for (int i = 0; i < NUM_SAMPLES; i++) {
        il_vec2 d = il_sample_concentric_disk(v2(il_pcg32_float(&rng), il_pcg32_float(&rng)));
        double r2 = (double)d.x * d.x + (double)d.y * d.y;
        if (r2 > 1.0 + 1e-6) outside++;
        double phi = atan2(d.y, d.x);
        if (phi < 0.0) phi += 2.0 * PI_D;
        int ir = (int)(r2 * NR), ip = (int)(phi / (2.0 * PI_D) * NPHI);
        ir = ir >= NR ? NR - 1 : ir;
        ip = ip >= NPHI ? NPHI - 1 : ip;
        obs[ir * NPHI + ip] += 1.0;
    }
    for (int i = 0; i < NR * NPHI; i++)
        expd[i] = (double)NUM_SAMPLES / (NR * NPHI);
    CHECK(outside == 0);
    CHECK(chi2_pvalue(obs, expd, NR * NPHI, "concentric disk") > g_alpha);
    /* The centre and the corners of the square map to the centre and the rim. */
    il_vec2 c = il_sample_concentric_disk(v2(0.5f, 0.5f));
    CHECK(c.x == 0.0f && c.y == 0.0f);
    il_vec2 e = il_sample_concentric_disk(v2(1.0f, 0.5f));
    CHECK_NEAR(e.x, 1.0, 1e-6);
    CHECK_NEAR(e.y, 0.0, 1e-6);
}

/* ------------------------------------------------------------- triangle */

static void test_triangle(void)
{
    /* Split the triangle into K^2 congruent sub-triangles; each should get
     * the same share of samples. */
    enum { K = 10, CELLS = K * K };
    static double obs[2 * K * K], expd[2 * K * K];
    memset(obs, 0, sizeof obs);
    il_pcg32 rng = il_pcg32_seed(5, 9);
    int outside = 0;
    for (int s = 0; s < NUM_SAMPLES; s++) {
        il_vec2 b = il_sample_triangle(v2(il_pcg32_float(&rng), il_pcg32_float(&rng)));
        if (b.x < 0.0f || b.y < 0.0f || b.x + b.y > 1.0f + 1e-6f) {
            outside++;
            continue;
        }
        double x = b.x * K, y = b.y * K;
        int i = (int)x, j = (int)y;
        if (i >= K) i = K - 1;
        if (j >= K) j = K - 1;
        int up = (x - i) + (y - j) < 1.0;
        if (!up && i + j > K - 2) { up = 1; }   /* rounding on the hypotenuse */
        obs[2 * (i * K + j) + up] += 1.0;
    }
    int valid = 0;
    for (int i = 0; i < K; i++)
        for (int j = 0; j < K; j++) {
            expd[2 * (i * K + j) + 1] = i + j <= K - 1 ? 1.0 : 0.0;
            expd[2 * (i * K + j)] = i + j <= K - 2 ? 1.0 : 0.0;
            valid += (i + j <= K - 1) + (i + j <= K - 2);
        }
    CHECK(valid == CELLS);
    for (int c = 0; c < 2 * K * K; c++)
        expd[c] *= (double)NUM_SAMPLES / CELLS;
    CHECK(outside == 0);
    double p = chi2_pvalue(obs, expd, 2 * K * K, "triangle");
    CHECK(p > g_alpha);
    /* Corners of the square land on the triangle. */
    il_vec2 b0 = il_sample_triangle(v2(0.0f, 0.0f));
    CHECK(b0.x == 0.0f && b0.y == 0.0f);
    il_vec2 b1 = il_sample_triangle(v2(0.999999f, 0.0f));
    CHECK_NEAR(b1.x, 1.0, 1e-5);
}

/* ------------------------------------------------------------ distrib1d */

static void test_distrib1d(void)
{
    il_error err = {0};
    il_distrib1d d;
    const float w[6] = {0.0f, 1.0f, 0.0f, 3.0f, 6.0f, 0.0f};
    CHECK_OK(il_distrib1d_init(&d, w, 6, &err), &err);
    CHECK(d.n == 6);
    CHECK_NEAR(d.integral, 10.0 / 6.0, 1e-6);
    CHECK(d.cdf[0] == 0.0f && d.cdf[6] == 1.0f);
    const double expect_pmf[6] = {0.0, 0.1, 0.0, 0.3, 0.6, 0.0};
    double sum_pmf = 0.0;
    for (uint32_t i = 0; i < 6; i++) {
        CHECK_NEAR(il_distrib1d_pmf(&d, i), expect_pmf[i], 1e-6);
        sum_pmf += il_distrib1d_pmf(&d, i);
    }
    CHECK_NEAR(sum_pmf, 1.0, 1e-6);
    CHECK(il_distrib1d_pmf(&d, 6) == 0.0f);   /* out of range */

    /* Edge values of u never pick an empty bin. */
    float pmf = -1.0f, ur = -1.0f;
    CHECK(il_distrib1d_sample_discrete(&d, 0.0f, &pmf, &ur) == 1);
    CHECK_NEAR(pmf, 0.1, 1e-6);
    CHECK(ur == 0.0f);
    CHECK(il_distrib1d_sample_discrete(&d, 0x1.fffffep-1f, &pmf, &ur) == 4);
    CHECK(ur < 1.0f);
    CHECK(il_distrib1d_sample_discrete(&d, 1.0f, NULL, &ur) == 4);    /* clamped */
    CHECK(ur < 1.0f);
    CHECK(il_distrib1d_sample_discrete(&d, -0.5f, NULL, NULL) == 1);  /* clamped */
    CHECK(il_distrib1d_sample_discrete(&d, 0.1f, NULL, NULL) == 3);   /* bin edge */
    CHECK(il_distrib1d_sample_discrete(&d, 0.25f, NULL, &ur) == 3);
    CHECK_NEAR(ur, 0.5, 1e-5);

    /* Frequencies follow the weights (chi-square), remapped u is uniform in
     * each bin (its mean is 1/2), the returned pmf matches. */
    double obs[6] = {0}, expd[6], ur_sum[6] = {0};
    il_pcg32 rng = il_pcg32_seed(42, 1);
    int pmf_bad = 0;
    for (int s = 0; s < NUM_SAMPLES; s++) {
        uint32_t i = il_distrib1d_sample_discrete(&d, il_pcg32_float(&rng), &pmf, &ur);
        obs[i] += 1.0;
        ur_sum[i] += ur;
        if (fabs(pmf - expect_pmf[i]) > 1e-6 || !(ur >= 0.0f && ur < 1.0f))
            pmf_bad++;
    }
    CHECK(pmf_bad == 0);
    for (int i = 0; i < 6; i++)
        expd[i] = expect_pmf[i] * NUM_SAMPLES;
    CHECK(obs[0] == 0.0 && obs[2] == 0.0 && obs[5] == 0.0);
    CHECK(chi2_pvalue(obs, expd, 6, "distrib1d") > g_alpha);
    for (int i = 1; i < 5; i++)
        if (obs[i] > 0.0)
            CHECK_NEAR(ur_sum[i] / obs[i], 0.5, 0.01);
    il_distrib1d_free(&d);
    CHECK(d.func == NULL && d.cdf == NULL && d.n == 0);

    /* All-zero weights: a uniform distribution. */
    const float z[4] = {0.0f, 0.0f, 0.0f, 0.0f};
    CHECK_OK(il_distrib1d_init(&d, z, 4, &err), &err);
    CHECK(d.integral == 0.0f);
    for (uint32_t i = 0; i < 4; i++)
        CHECK_NEAR(il_distrib1d_pmf(&d, i), 0.25, 1e-7);
    CHECK(il_distrib1d_sample_discrete(&d, 0.3f, &pmf, &ur) == 1);
    CHECK_NEAR(pmf, 0.25, 1e-7);
    CHECK_NEAR(ur, 0.2, 1e-5);
    il_distrib1d_free(&d);

    /* A single bin. */
    const float one = 2.0f;
    CHECK_OK(il_distrib1d_init(&d, &one, 1, &err), &err);
    CHECK(il_distrib1d_sample_discrete(&d, 0.7f, &pmf, &ur) == 0);
    CHECK(pmf == 1.0f);
    CHECK_NEAR(ur, 0.7, 1e-6);
    il_distrib1d_free(&d);

    /* Errors: no bins, negative or NaN weights, no weights. */
    CHECK(il_distrib1d_init(&d, w, 0, &err) == IL_ERR_INVALID);
    CHECK(err.status == IL_ERR_INVALID && strstr(err.message, "n == 0") != NULL);
    CHECK(d.func == NULL && d.cdf == NULL);
    const float neg[3] = {1.0f, -1.0f, 2.0f};
    CHECK(il_distrib1d_init(&d, neg, 3, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "weight 1") != NULL);
    const float nan_w[2] = {1.0f, NAN};
    CHECK(il_distrib1d_init(&d, nan_w, 2, &err) == IL_ERR_INVALID);
    const float inf_w[2] = {INFINITY, 1.0f};
    CHECK(il_distrib1d_init(&d, inf_w, 2, &err) == IL_ERR_INVALID);
    CHECK(il_distrib1d_init(&d, NULL, 2, &err) == IL_ERR_INVALID);
    il_distrib1d_free(&d);   /* freeing a failed distribution is safe */

    /* A long table with a spike: the spike bin and its neighbours. */
    enum { N = 100000 };
    float *big = calloc(N, sizeof(float));
    big[N - 1] = 1.0f;
    big[12345] = 1.0f;
    CHECK_OK(il_distrib1d_init(&d, big, N, &err), &err);
    CHECK(il_distrib1d_sample_discrete(&d, 0.0f, NULL, NULL) == 12345);
    CHECK(il_distrib1d_sample_discrete(&d, 0.49f, NULL, NULL) == 12345);
    CHECK(il_distrib1d_sample_discrete(&d, 0.5f, NULL, NULL) == N - 1);
    CHECK(il_distrib1d_sample_discrete(&d, 0.99f, NULL, NULL) == N - 1);
    CHECK_NEAR(il_distrib1d_pmf(&d, 12345), 0.5, 1e-6);
    il_distrib1d_free(&d);
    free(big);
}

/* ---------------------------------------------------------------- other */

static void test_power_heuristic(void)
{
    CHECK_NEAR(il_power_heuristic(1.0f, 1.0f), 0.5, 1e-7);
    CHECK_NEAR(il_power_heuristic(3.0f, 1.0f), 0.9, 1e-6);
    CHECK_NEAR(il_power_heuristic(3.0f, 1.0f) + il_power_heuristic(1.0f, 3.0f), 1.0, 1e-6);
    CHECK(il_power_heuristic(0.0f, 0.0f) == 0.0f);
    CHECK(il_power_heuristic(2.0f, 0.0f) == 1.0f);
}

static void test_pdf_values(void)
{
    CHECK_NEAR(il_cosine_hemisphere_pdf(1.0f), 1.0 / PI_D, 1e-7);
    CHECK(il_cosine_hemisphere_pdf(-0.5f) == 0.0f);
    CHECK_NEAR(il_uniform_cone_pdf(0.5f), 1.0 / PI_D, 1e-6);
    CHECK_NEAR(il_phong_lobe_pdf(1.0f, 10.0f), 11.0 / (2.0 * PI_D), 1e-6);
    CHECK(il_phong_lobe_pdf(-0.1f, 10.0f) == 0.0f);
    /* The Phong lobe with exponent 1 is the cosine lobe. */
    CHECK_NEAR(il_phong_lobe_pdf(0.3f, 1.0f), il_cosine_hemisphere_pdf(0.3f), 1e-6);
    /* Cone with cos_max = -1 is the whole sphere. */
    CHECK_NEAR(il_uniform_cone_pdf(-1.0f), 1.0 / (4.0 * PI_D), 1e-7);
    /* The cone's samples stay in the cone. */
    il_pcg32 rng = il_pcg32_seed(3, 3);
    int outside = 0;
    for (int i = 0; i < 10000; i++) {
        il_vec3 d = il_sample_uniform_cone(v2(il_pcg32_float(&rng), il_pcg32_float(&rng)), 0.9f);
        if (d.z < 0.9f - 1e-6f) outside++;
    }
    CHECK(outside == 0);
    /* A cone as narrow as the sun's (0.2665 degrees): sin and 1 - cos of
     * each direction as in double, not after cancellation in 1 - c^2. */
    float cos_sun = cosf(0.2665f * (float)PI_D / 180.0f);
    double worst = 0.0;
    for (int i = 0; i < 10000; i++) {
        il_vec2 u = v2(il_pcg32_float(&rng), il_pcg32_float(&rng));
        il_vec3 d = il_sample_uniform_cone(u, cos_sun);
        double omc = (double)u.x * (1.0 - (double)cos_sun), s = sqrt(omc * (2.0 - omc));
        if (s > 1e-4)
            worst = fmax(worst, fabs(hypot(d.x, d.y) - s) / s);
    }
    printf("sun-sized cone: sin within %.2g of double\n", worst);
    CHECK(worst < 1e-4);
}

/* il_sample_cosine_hemisphere_n (eight lanes of AVX2 where the CPU has it)
 * gives il_sample_cosine_hemisphere's results bit for bit: random points,
 * the corners, the centre, both diagonals and the axes of the concentric
 * map, for every count from 0 to 19 (partial groups of eight). */
static void test_cosine_hemisphere_n(void)
{
    enum { N = 4096 };
    static il_vec2 u[N];
    static il_vec3 a[N], b[N];
    il_pcg32 rng = il_pcg32_seed(77, 5);
    uint32_t n = 0;
    const float special[] = {0.0f, 0.25f, 0.5f, 0.75f, 0x1.fffffep-1f, 0x1p-24f, 0.5f - 0x1p-24f};
    const uint32_t ns = sizeof special / sizeof special[0];
    for (uint32_t i = 0; i < ns; i++)
        for (uint32_t j = 0; j < ns; j++)
            u[n++] = v2(special[i], special[j]);
    while (n < N) {
        float x = il_pcg32_float(&rng);
        /* Every fourth point on a diagonal |2x-1| = |2y-1|. */
        u[n] = (n % 4 == 0) ? v2(x, n % 8 == 0 ? x : 1.0f - x) : v2(x, il_pcg32_float(&rng));
        n++;
    }
    for (uint32_t i = 0; i < N; i++)
        a[i] = il_sample_cosine_hemisphere(u[i]);
    il_sample_cosine_hemisphere_n(u, b, N);
    CHECK(memcmp(a, b, sizeof a) == 0);
    for (uint32_t count = 0; count < 20; count++) {
        memset(b, 0xff, sizeof(il_vec3) * 21);
        il_sample_cosine_hemisphere_n(u + 3, b, count);
        CHECK(memcmp(a + 3, b, sizeof(il_vec3) * count) == 0);
        CHECK(b[count].x != b[count].x);   /* nothing written past the end (NaN fill) */
    }
    /* The centre maps to the pole. */
    il_sample_cosine_hemisphere_n(&(il_vec2){0.5f, 0.5f}, b, 1);
    CHECK(b[0].x == 0.0f && b[0].y == 0.0f && b[0].z == 1.0f);
}

/* il_cdf_find (the branch-free search) against a linear scan for the last
 * bin with cdf[i] <= u, on CDFs with zero-width bins, every length 1..40. */
static void test_cdf_find(void)
{
    il_pcg32 rng = il_pcg32_seed(3, 9);
    float cdf[41];
    for (uint32_t n = 1; n <= 40; n++) {
        cdf[0] = 0.0f;
        for (uint32_t i = 1; i <= n; i++) /* about a third of the bins empty */
            cdf[i] = cdf[i - 1] + (il_pcg32_float(&rng) < 0.33f ? 0.0f : il_pcg32_float(&rng));
        for (uint32_t i = 1; i <= n; i++)
            cdf[i] /= cdf[n] > 0.0f ? cdf[n] : 1.0f;
        for (int k = 0; k < 200; k++) {
            float u = k < 41 ? cdf[k % (n + 1)] : il_pcg32_float(&rng); /* bin edges too */
            if (u >= 1.0f)
                u = 0x1.fffffep-1f;
            uint32_t want = 0;
            for (uint32_t i = 0; i < n; i++)
                if (cdf[i] <= u)
                    want = i;
            CHECK(il_cdf_find(cdf, n, u) == want);
        }
    }
}

/* il_distrib1d_sample_discrete (guided by its table) against il_cdf_find
 * over the whole CDF: the same bin for every u, on distributions of 1 to
 * 2000 bins with empty bins, single spikes and a long tail, at random u,
 * at the guide cells' edges k/n and one float either side, and at the
 * CDF's own values. */
static void test_distrib1d_guide(void)
{
    il_pcg32 rng = il_pcg32_seed(5, 17);
    static float w[2000];
    const uint32_t sizes[] = {1, 2, 3, 7, 16, 100, 513, 1024, 2000};
    int mismatches = 0, tried = 0;
    for (size_t z = 0; z < sizeof sizes / sizeof sizes[0]; z++) {
        uint32_t n = sizes[z];
        for (int shape = 0; shape < 4; shape++) {
            for (uint32_t i = 0; i < n; i++) {
                float r = il_pcg32_float(&rng);
                w[i] = shape == 0 ? r                                  /* random */
                     : shape == 1 ? (r < 0.5f ? 0.0f : r)               /* half empty */
                     : shape == 2 ? (i == n / 3 ? 1000.0f : 1e-4f * r)  /* one spike */
                                  : powf(r, 8.0f);                      /* a long tail */
            }
            il_distrib1d d;
            il_error err = {0};
            CHECK_OK(il_distrib1d_init(&d, w, n, &err), &err);
            for (uint32_t k = 0; k < 3 * n + 600; k++) {
                float u;
                if (k < 3 * n) {
                    float edge = (float)((double)(k / 3) / n);
                    u = k % 3 == 0 ? edge : (k % 3 == 1 ? nextafterf(edge, 0.0f) : nextafterf(edge, 1.0f));
                } else if (k < 3 * n + 300) {
                    u = d.cdf[il_pcg32_next(&rng) % n];
                } else {
                    u = il_pcg32_float(&rng);
                }
                if (!(u < 1.0f))
                    u = 0x1.fffffep-1f;
                tried++;
                mismatches += il_distrib1d_sample_discrete(&d, u, NULL, NULL) != il_cdf_find(d.cdf, n, u);
            }
            il_distrib1d_free(&d);
        }
    }
    printf("distrib1d guide: %d of %d draws differ from the full search\n", mismatches, tried);
    CHECK(mismatches == 0);
}

int main(void)
{
    g_alpha = chi2_significance(0.01, NUM_CHI2_TESTS);
    const warp warps[] = {
        {"cosine hemisphere", W_COSINE, 0.0f},
        {"uniform hemisphere", W_HEMI, 0.0f},
        {"uniform sphere", W_SPHERE, 0.0f},
        {"uniform cone 0.7", W_CONE, 0.7f},
        {"uniform cone -0.35", W_CONE, -0.35f},
        {"phong lobe n=1", W_PHONG, 1.0f},
        {"phong lobe n=10", W_PHONG, 10.0f},
        {"phong lobe n=100", W_PHONG, 100.0f},
        {"phong lobe n=1000", W_PHONG, 1000.0f},
    };
    for (size_t i = 0; i < sizeof warps / sizeof warps[0]; i++) {
        test_warp_pdf_integrates_to_one(&warps[i]);
        test_warp_chi2(&warps[i], 1000 + i);
    }
    test_concentric_disk();
    test_triangle();
    test_distrib1d();
    test_power_heuristic();
    test_pdf_values();
    test_cosine_hemisphere_n();
    test_cdf_find();
    test_distrib1d_guide();
    return check_report();
}
