/* Form factors: Lambert's contour formula, the ray-cast and hemicube rows
 * and the row cache, against closed forms from Howell's "A Catalog of
 * Radiation Heat Transfer Configuration Factors" (B-13: differential area to
 * a coaxial parallel disc; C-11: parallel aligned rectangles; C-14:
 * perpendicular rectangles with a common edge) and against the properties
 * every form-factor matrix has (reciprocity, row sums in a closed box, no
 * self-term, sorted positive rows, determinism). */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/error.h"
#include "methods/radiosity/rad_ff_internal.h"

#define PI_D 3.14159265358979323846

/* ------------------------------------------------------------ closed forms */

/* Howell B-13: dA to a coaxial parallel disc of radius r at height h. */
static double ff_point_disc(double r, double h) { return r * r / (r * r + h * h); }

/* Howell B-3: dA parallel to an a x b rectangle at distance c, on the normal
 * through one of its corners. */
static double ff_point_rect_corner(double a, double b, double c)
{
    double A = a / c, B = b / c;
    return (A / sqrt(1 + A * A) * atan(B / sqrt(1 + A * A)) +
            B / sqrt(1 + B * B) * atan(A / sqrt(1 + B * B))) / (2 * PI_D);
}

/* Howell C-11: parallel aligned a x b rectangles at distance c. */
static double ff_parallel(double a, double b, double c)
{
    double X = a / c, Y = b / c;
    double s = log(sqrt((1 + X * X) * (1 + Y * Y) / (1 + X * X + Y * Y))) +
               X * sqrt(1 + Y * Y) * atan(X / sqrt(1 + Y * Y)) +
               Y * sqrt(1 + X * X) * atan(Y / sqrt(1 + X * X)) - X * atan(X) - Y * atan(Y);
    return 2 / (PI_D * X * Y) * s;
}

/* Howell C-14: from a w x l rectangle to an h x l one at 90 degrees sharing
 * the edge of length l. */
static double ff_perpendicular(double w, double h, double l)
{
    double H = h / l, W = w / l, H2 = H * H, W2 = W * W, S = H2 + W2;
    double lg = log((1 + W2) * (1 + H2) / (1 + S)) +
                W2 * log(W2 * (1 + S) / ((1 + W2) * S)) + H2 * log(H2 * (1 + S) / ((1 + H2) * S));
    return (W * atan(1 / W) + H * atan(1 / H) - sqrt(S) * atan(1 / sqrt(S)) + 0.25 * lg) / (PI_D * W);
}

/* --------------------------------------------------- a hand-built mesh */

/* Quads o + u*eu + v*ev, split into nu x nv patches (front: eu x ev), or
 * into plain occluder triangles (patch = false: mirror-like, no patches). */
typedef struct builder {
    il_patch_mesh m;
    uint32_t cap_v, cap_p, cap_t;
} builder;

static void grow(void **p, uint32_t *cap, uint32_t need, size_t elem)
{
    if (need <= *cap)
        return;
    uint32_t c = *cap ? *cap : 64;
    while (c < need)
        c *= 2;
    *p = realloc(*p, (size_t)c * elem);
    *cap = c;
}

static uint32_t add_vertex(builder *b, il_vec3 p)
{
    uint32_t cap = b->cap_v;
    /* +1 vertex of padding for Embree's 16-byte reads */
    grow((void **)&b->m.positions, &cap, b->m.num_vertices + 2, sizeof(il_vec3));
    b->cap_v = cap;
    b->m.positions[b->m.num_vertices] = p;
    return b->m.num_vertices++;
}

static void add_tri(builder *b, uint32_t a, uint32_t c, uint32_t d, uint32_t patch)
{
    uint32_t cap = b->cap_t;
    grow((void **)&b->m.tri_indices, &cap, 3 * (b->m.num_tris + 1), sizeof(uint32_t));
    cap = b->cap_t;
    grow((void **)&b->m.tri_patch, &cap, b->m.num_tris + 1, sizeof(uint32_t));
    b->cap_t = cap;
    uint32_t *t = b->m.tri_indices + 3 * b->m.num_tris;
    t[0] = a;
    t[1] = c;
    t[2] = d;
    b->m.tri_patch[b->m.num_tris++] = patch;
}

static il_vec3 at(il_vec3 o, il_vec3 eu, il_vec3 ev, double u, double v)
{
    return v3_add(o, v3_add(v3_scale(eu, (float)u), v3_scale(ev, (float)v)));
}

static void add_grid(builder *b, il_vec3 o, il_vec3 eu, il_vec3 ev, int nu, int nv, bool patch)
{
    il_vec3 n = v3_normalize(v3_cross(eu, ev));
    float area = v3_length(v3_cross(eu, ev)) / (float)(nu * nv);
    for (int y = 0; y < nv; y++) {
        for (int x = 0; x < nu; x++) {
            il_vec3 c[4] = {at(o, eu, ev, (double)x / nu, (double)y / nv),
                            at(o, eu, ev, (double)(x + 1) / nu, (double)y / nv),
                            at(o, eu, ev, (double)(x + 1) / nu, (double)(y + 1) / nv),
                            at(o, eu, ev, (double)x / nu, (double)(y + 1) / nv)};
            uint32_t v[4];
            for (int k = 0; k < 4; k++)
                v[k] = add_vertex(b, c[k]);
            uint32_t id = IL_NO_PATCH;
            if (patch) {
                uint32_t cap = b->cap_p;
                grow((void **)&b->m.patches, &cap, b->m.num_patches + 1, sizeof(il_patch));
                b->cap_p = cap;
                id = b->m.num_patches++;
                il_patch *p = &b->m.patches[id];
                memset(p, 0, sizeof *p);
                p->num_corners = 4;
                memcpy(p->v, v, sizeof v);
                p->center = v3_scale(v3_add(v3_add(c[0], c[1]), v3_add(c[2], c[3])), 0.25f);
                p->normal = n;
                p->area = area;
                p->rho = v3s(0.5f);
            }
            add_tri(b, v[0], v[1], v[2], id);
            add_tri(b, v[0], v[2], v[3], id);
        }
    }
}

static il_patch_mesh *finish(builder *b)
{
    il_error err;
    il_patch_mesh *m = calloc(1, sizeof *m);
    *m = b->m;
    CHECK_OK(il_tracer_create_triangles(m->positions, m->num_vertices, m->tri_indices, m->num_tris,
                                        &m->tracer, &err), &err);
    memset(b, 0, sizeof *b);
    return m;
}

static void free_mesh(il_patch_mesh *m)
{
    il_tracer_release(m->tracer);
    free(m->positions);
    free(m->patches);
    free(m->tri_indices);
    free(m->tri_patch);
    free(m);
}

/* Two unit squares: the shooter at z = 0 facing +z split ns x ns, the
 * receiver at z = 1 facing down (or up when flipped) split nr x nr. */
static il_patch_mesh *parallel_pair(int ns, int nr, bool flip, bool occluder)
{
    builder b = {0};
    add_grid(&b, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), ns, ns, true);
    if (flip)
        add_grid(&b, v3(0, 0, 1), v3(1, 0, 0), v3(0, 1, 0), nr, nr, true);
    else
        add_grid(&b, v3(0, 0, 1), v3(0, 1, 0), v3(1, 0, 0), nr, nr, true);
    if (occluder)
        add_grid(&b, v3(-1, -1, 0.5f), v3(3, 0, 0), v3(0, 3, 0), 1, 1, false);
    return finish(&b);
}

/* The shooter square z = 0 (facing +z, split ns x ns), a one-sided 3 x 3
 * patch at z = 0.5 also facing +z (its back towards the shooter, like the
 * back of a lamp hanging below a ceiling) and the receiver square z = 1
 * facing down: every segment from the shooter to the receiver crosses the
 * middle panel, so the shooter sees nothing and the receiver sees the
 * panel's front only. */
static il_patch_mesh *back_panel(int ns)
{
    builder b = {0};
    add_grid(&b, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), ns, ns, true);
    add_grid(&b, v3(-1, -1, 0.5f), v3(3, 0, 0), v3(0, 3, 0), 1, 1, true);
    add_grid(&b, v3(0, 0, 1), v3(0, 1, 0), v3(1, 0, 0), 1, 1, true);
    return finish(&b);
}

/* The floor square z = 0 (y in [0,1], facing +z) and the wall y = 0
 * (z in [0,1], facing +y): perpendicular with the common edge along x. */
static il_patch_mesh *perpendicular_pair(int ns, int nr)
{
    builder b = {0};
    add_grid(&b, v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), ns, ns, true);
    add_grid(&b, v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 0), nr, nr, true);
    return finish(&b);
}

/* A closed lx x ly x lz box, faces facing inwards, n x n patches per face. */
static il_patch_mesh *closed_box(float lx, float ly, float lz, int n)
{
    builder b = {0};
    add_grid(&b, v3(0, 0, 0), v3(0, 0, lz), v3(lx, 0, 0), n, n, true);
    add_grid(&b, v3(0, ly, 0), v3(lx, 0, 0), v3(0, 0, lz), n, n, true);
    add_grid(&b, v3(0, 0, 0), v3(0, ly, 0), v3(0, 0, lz), n, n, true);
    add_grid(&b, v3(lx, 0, 0), v3(0, 0, lz), v3(0, ly, 0), n, n, true);
    add_grid(&b, v3(0, 0, 0), v3(lx, 0, 0), v3(0, ly, 0), n, n, true);
    add_grid(&b, v3(0, 0, lz), v3(0, ly, 0), v3(lx, 0, 0), n, n, true);
    return finish(&b);
}

static double row_sum(const il_ff_row *r, uint32_t from, uint32_t to)
{
    double s = 0.0;
    for (uint32_t k = 0; k < r->count; k++)
        if (r->index[k] >= from && r->index[k] < to)
            s += r->value[k];
    return s;
}

static il_ff_row new_row(uint32_t n)
{
    il_ff_row r = {0, malloc(n * sizeof(uint32_t)), malloc(n * sizeof(float))};
    return r;
}

static void free_row(il_ff_row *r)
{
    free(r->index);
    free(r->value);
}

/* Rows sorted by j, positive, without the self-term. */
static bool row_well_formed(const il_ff_row *r, uint32_t i, uint32_t n)
{
    for (uint32_t k = 0; k < r->count; k++) {
        if (r->index[k] >= n || r->index[k] == i || !(r->value[k] > 0.0f))
            return false;
        if (k > 0 && r->index[k] <= r->index[k - 1])
            return false;
    }
    return true;
}

/* ---------------------------------------------------------------- tests */

static void test_point_polygon(void)
{
    il_vec3 o = v3(0, 0, 0), up = v3(0, 0, 1);
    /* B-13 with a 4096-gon inscribed in the disc (area error ~4e-7). */
    enum { N = 4096 };
    static il_vec3 disc[N];
    double r = 0.7, h = 1.3;
    for (int k = 0; k < N; k++) {
        double a = -2.0 * PI_D * k / N; /* clockwise seen from above: front faces down */
        disc[k] = v3((float)(r * cos(a)), (float)(r * sin(a)), (float)h);
    }
    CHECK_REL(il_ff_point_polygon(o, up, disc, N), ff_point_disc(r, h), 2e-5);

    /* B-3: a 2 x 3 rectangle at distance 1.5 above its corner. */
    il_vec3 rect[4] = {v3(0, 0, 1.5f), v3(0, 3, 1.5f), v3(2, 3, 1.5f), v3(2, 0, 1.5f)};
    CHECK_REL(il_ff_point_polygon(o, up, rect, 4), ff_point_rect_corner(2, 3, 1.5), 1e-6);
    /* The same rectangle about its centre: four corner rectangles. */
    il_vec3 centred[4] = {v3(-1, -1.5f, 1.5f), v3(-1, 1.5f, 1.5f), v3(1, 1.5f, 1.5f), v3(1, -1.5f, 1.5f)};
    CHECK_REL(il_ff_point_polygon(o, up, centred, 4), 4 * ff_point_rect_corner(1, 1.5, 1.5), 1e-6);

    /* Clipping: the half of a wall below the tangent plane contributes nothing. */
    il_vec3 wall_full[4] = {v3(-1, 1, -1), v3(1, 1, -1), v3(1, 1, 1), v3(-1, 1, 1)};
    il_vec3 wall_half[4] = {v3(-1, 1, 0), v3(1, 1, 0), v3(1, 1, 1), v3(-1, 1, 1)};
    double full = il_ff_point_polygon(o, up, wall_full, 4);
    CHECK(full > 0.01);
    CHECK_NEAR(full, il_ff_point_polygon(o, up, wall_half, 4), 1e-12);
    /* Wholly behind, in the tangent plane, or degenerate: zero. */
    il_vec3 below[4] = {v3(0, 0, -1), v3(0, 1, -1), v3(1, 1, -1), v3(1, 0, -1)};
    CHECK_NEAR(il_ff_point_polygon(o, up, below, 4), 0.0, 0.0);
    CHECK_NEAR(il_ff_point_polygon(o, up, rect, 2), 0.0, 0.0);
    /* A polygon covering the hemisphere's whole view: F = 1. */
    il_vec3 huge[4] = {v3(-1e4f, -1e4f, 1), v3(-1e4f, 1e4f, 1), v3(1e4f, 1e4f, 1), v3(1e4f, -1e4f, 1)};
    CHECK_NEAR(il_ff_point_polygon(o, up, huge, 4), 1.0, 1e-3);
}

/* Area-to-area by averaging the point values over a midpoint grid. */
static double area_average(il_vec3 o, il_vec3 eu, il_vec3 ev, const il_vec3 *poly, int m)
{
    il_vec3 n = v3_normalize(v3_cross(eu, ev));
    double s = 0.0;
    for (int y = 0; y < m; y++)
        for (int x = 0; x < m; x++)
            s += il_ff_point_polygon(at(o, eu, ev, (x + 0.5) / m, (y + 0.5) / m), n, poly, 4);
    return s / ((double)m * m);
}

static void test_area_to_area_analytic(void)
{
    CHECK_NEAR(ff_parallel(1, 1, 1), 0.19982, 1e-5);
    CHECK_NEAR(ff_perpendicular(1, 1, 1), 0.20004, 1e-5);
    il_vec3 top[4] = {v3(0, 0, 1), v3(0, 1, 1), v3(1, 1, 1), v3(1, 0, 1)};
    CHECK_REL(area_average(v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), top, 64), ff_parallel(1, 1, 1), 0.005);
    /* A 2 x 1 pair at distance 0.5 too. */
    il_vec3 top2[4] = {v3(0, 0, 0.5f), v3(0, 1, 0.5f), v3(2, 1, 0.5f), v3(2, 0, 0.5f)};
    CHECK_REL(area_average(v3(0, 0, 0), v3(2, 0, 0), v3(0, 1, 0), top2, 64), ff_parallel(2, 1, 0.5), 0.005);
    /* C-14: floor w = 1 (y in [0,1]) to the wall h = 2 (z in [0,2]), l = 1. */
    il_vec3 wall[4] = {v3(0, 0, 0), v3(0, 0, 2), v3(1, 0, 2), v3(1, 0, 0)};
    CHECK_REL(area_average(v3(0, 0, 0), v3(1, 0, 0), v3(0, 1, 0), wall, 128), ff_perpendicular(1, 2, 1), 0.005);
}

static void test_ray_closed_forms(void)
{
    float *scratch = calloc(8, sizeof(float));
    il_ff_row row = new_row(8);
    il_patch_mesh *m = parallel_pair(1, 1, false, false);
    il_ff_ray_row(m, 1u << 20, 7, 0, scratch, &row);
    CHECK(row.count == 1 && row.index[0] == 1);
    CHECK_REL(row.value[0], 0.19982, 0.01);
    il_ff_ray_row(m, 1u << 20, 7, 1, scratch, &row);
    CHECK(row.count == 1 && row.index[0] == 0);
    CHECK_REL(row.value[0], 0.19982, 0.01);
    free_mesh(m);

    m = perpendicular_pair(1, 1);
    il_ff_ray_row(m, 1u << 20, 7, 0, scratch, &row);
    CHECK(row.count == 1);
    CHECK_REL(row_sum(&row, 1, 2), 0.20004, 0.01);
    free_mesh(m);

    /* Tracing in direction order (with the buffer) or in sample order
     * (without) gives the same row, bit for bit. */
    m = parallel_pair(2, 3, false, false);
    {
        il_ff_row r1 = new_row(13), r2 = new_row(13);
        float *tally = calloc(13, sizeof(float));
        il_vec2 *order = malloc(2 * 5000 * sizeof *order);
        il_ff_ray_row_ordered(m, 5000, 9, 1, tally, order, &r1);
        il_ff_ray_row_ordered(m, 5000, 9, 1, tally, NULL, &r2);
        CHECK(r1.count == 9 && r2.count == r1.count &&
              memcmp(r1.index, r2.index, r1.count * sizeof *r1.index) == 0 &&
              memcmp(r1.value, r2.value, r1.count * sizeof *r1.value) == 0);
        free(order);
        free(tally);
        free_row(&r1);
        free_row(&r2);
    }
    free_mesh(m);

    /* Seen from the back, or behind a mirror-like occluder: nothing. */
    m = parallel_pair(1, 1, true, false);
    il_ff_ray_row(m, 1u << 14, 7, 0, scratch, &row);
    CHECK(row.count == 0);
    free_mesh(m);
    m = parallel_pair(1, 1, false, true);
    il_ff_ray_row(m, 1u << 14, 7, 0, scratch, &row);
    CHECK(row.count == 0);
    free_mesh(m);
    for (int k = 0; k < 8; k++)
        CHECK(scratch[k] == 0.0f);
    free_row(&row);
    free(scratch);
}

static void hemicube_row_of(il_patch_mesh *m, uint32_t res, uint32_t i, il_ff_row *row)
{
    il_error err;
    il_hemicube *hc = NULL;
    il_hemicube_buffers *buf = NULL;
    CHECK_OK(il_hemicube_create(m, res, &hc, &err), &err);
    CHECK_OK(il_hemicube_buffers_create(hc, &buf, &err), &err);
    il_hemicube_row(hc, buf, i, row);
    il_hemicube_buffers_release(buf);
    il_hemicube_release(hc);
}

static void test_hemicube_closed_forms(void)
{
    il_error err;
    enum { NR = 8, NS = 8 };
    il_ff_row row = new_row(NS * NS + NR * NR + 2);
    il_vec3 o = v3(0.5f, 0.5f, 0), up = v3(0, 0, 1);

    /* Point-to-area: one shooter patch, the receiver split NR x NR. */
    il_patch_mesh *m = parallel_pair(1, NR, false, false);
    hemicube_row_of(m, 256, 0, &row);
    CHECK(row_well_formed(&row, 0, m->num_patches));
    CHECK(row.count == NR * NR);
    il_vec3 top[4] = {v3(0, 0, 1), v3(0, 1, 1), v3(1, 1, 1), v3(1, 0, 1)};
    CHECK_REL(row_sum(&row, 1, 1 + NR * NR), il_ff_point_polygon(o, up, top, 4), 0.02);
    free_mesh(m);

    m = perpendicular_pair(1, NR);
    hemicube_row_of(m, 256, 0, &row);
    CHECK(row_well_formed(&row, 0, m->num_patches));
    il_vec3 wall[4] = {v3(0, 0, 0), v3(0, 0, 1), v3(1, 0, 1), v3(1, 0, 0)};
    CHECK_REL(row_sum(&row, 1, 1 + NR * NR), il_ff_point_polygon(o, up, wall, 4), 0.02);
    free_mesh(m);

    /* Area-to-area: the shooter split too, rows averaged by area (equal
     * areas here), against C-11 and C-14. */
    for (int perp = 0; perp < 2; perp++) {
        m = perp ? perpendicular_pair(NS, NR) : parallel_pair(NS, NR, false, false);
        il_hemicube *hc = NULL;
        il_hemicube_buffers *buf = NULL;
        CHECK_OK(il_hemicube_create(m, 256, &hc, &err), &err);
        CHECK_OK(il_hemicube_buffers_create(hc, &buf, &err), &err);
        double s = 0.0;
        for (uint32_t i = 0; i < NS * NS; i++) {
            il_hemicube_row(hc, buf, i, &row);
            s += row_sum(&row, NS * NS, NS * NS + NR * NR);
        }
        CHECK_REL(s / (NS * NS), perp ? ff_perpendicular(1, 1, 1) : ff_parallel(1, 1, 1), 0.02);
        il_hemicube_buffers_release(buf);
        il_hemicube_release(hc);
        free_mesh(m);
    }

    /* Back faces receive nothing; mirror-like occluders hide. */
    m = parallel_pair(1, 1, true, false);
    hemicube_row_of(m, 64, 0, &row);
    CHECK(row.count == 0);
    free_mesh(m);
    m = parallel_pair(1, 1, false, true);
    hemicube_row_of(m, 64, 0, &row);
    CHECK(row.count == 0);
    free_mesh(m);

    /* A one-sided patch seen from its back occludes (it receives nothing)
     * in both back-ends: the shooters below it see neither it nor the
     * receiver above it; the receiver sees the panel's front, and the
     * hemicube agrees with ray casting on how much. */
    m = back_panel(2);
    float *scratch = calloc(m->num_patches, sizeof(float));
    for (uint32_t i = 0; i < 4; i++) {
        hemicube_row_of(m, 128, i, &row);
        CHECK(row.count == 0);
        il_ff_ray_row(m, 1u << 14, 5, i, scratch, &row);
        CHECK(row.count == 0);
    }
    hemicube_row_of(m, 256, 5, &row);
    CHECK(row.count == 1 && row.index[0] == 4);
    double hemi = row_sum(&row, 0, m->num_patches);
    il_ff_ray_row(m, 1u << 18, 5, 5, scratch, &row);
    CHECK(row.count == 1 && row.index[0] == 4);
    CHECK(hemi > 0.5);
    CHECK_NEAR(hemi, row_sum(&row, 0, m->num_patches), 0.02);
    free(scratch);
    free_mesh(m);

    il_hemicube *hc = NULL;
    CHECK(il_hemicube_create(m, 0, &hc, &err) == IL_ERR_INVALID && hc == NULL);
    free_row(&row);
}

/* Reciprocity and row sums in a closed box with both back-ends through il_ff. */
static void test_closed_box(il_form_factor_method method, double recip_tol)
{
    il_error err;
    il_patch_mesh *m = closed_box(1.0f, 0.75f, 1.25f, 4);
    uint32_t n = m->num_patches;
    il_rad_settings s;
    memset(&s, 0, sizeof s);
    s.form_factors = method;
    s.hemicube_resolution = 128;
    s.ray_samples = 1u << 16;
    s.seed = 3;
    s.threads = 1;
    il_ff *ff = NULL;
    il_ff_work *w = NULL, *w2 = NULL;
    CHECK_OK(il_ff_create(m, &s, &ff, &err), &err);
    CHECK_OK(il_ff_work_create(ff, &w, &err), &err);
    CHECK_OK(il_ff_work_create(ff, &w2, &err), &err);
    float *F = calloc((size_t)n * n, sizeof(float));
    bool formed = true;
    double worst_sum = 0.0;
    for (uint32_t i = 0; i < n; i++) {
        const il_ff_row *r = il_ff_compute_row(ff, w, i);
        formed &= row_well_formed(r, i, n);
        double sum = 0.0;
        for (uint32_t k = 0; k < r->count; k++) {
            F[(size_t)i * n + r->index[k]] = r->value[k];
            sum += r->value[k];
        }
        worst_sum = fmax(worst_sum, fabs(sum - 1.0));
    }
    CHECK(formed);
    CHECK(worst_sum < 0.01);
    for (uint32_t i = 0; i < n; i++)
        CHECK(F[(size_t)i * n + i] == 0.0f);
    /* Reciprocity A_i F_ij = A_j F_ji.  Ray-cast: every pair within 5.5
     * standard deviations of the binomial counts (about 4,500 pairs), and
     * the matrix as a whole within recip_tol.  Hemicube: a point-to-area
     * method (at the patch centre), so reciprocity holds only as far as the
     * form factor varies little over the patch: checked over pairs more
     * than two patch widths apart, and each value against the analytic
     * point-to-patch value at the centre (the box is convex: no occlusion). */
    double diff = 0.0, total = 0.0, worst = 0.0, worst_point = 0.0;
    for (uint32_t i = 0; i < n; i++) {
        for (uint32_t j = i + 1; j < n; j++) {
            const il_patch *pi = &m->patches[i], *pj = &m->patches[j];
            double fij = F[(size_t)i * n + j], fji = F[(size_t)j * n + i];
            double a = pi->area * fij, b = pj->area * fji;
            if (method == IL_FF_RAYCAST) {
                double var = pi->area * pi->area * fij * (1 - fij) / s.ray_samples +
                             pj->area * pj->area * fji * (1 - fji) / s.ray_samples;
                if (var > 0)
                    worst = fmax(worst, fabs(a - b) / sqrt(var));
            } else {
                if (v3_length(v3_sub(pi->center, pj->center)) < 0.6f)
                    continue;
                il_vec3 poly[4];
                for (int k = 0; k < 4; k++)
                    poly[k] = m->positions[pj->v[k]];
                double exact = v3_dot(pi->normal, pj->normal) > 0.99f
                                   ? 0.0 : il_ff_point_polygon(pi->center, pi->normal, poly, 4);
                worst_point = fmax(worst_point, fabs(exact - fij));
            }
            diff += fabs(a - b);
            total += a + b;
        }
    }
    CHECK(diff / total < recip_tol);
    if (method == IL_FF_RAYCAST)
        CHECK(worst < 5.5);
    else
        CHECK(worst_point < 0.002);
    /* Determinism: the same row again, in another work, is bit-identical. */
    const il_ff_row *r1 = il_ff_compute_row(ff, w, 17);
    uint32_t c1 = r1->count;
    uint32_t *i1 = malloc(c1 * sizeof *i1);
    float *v1 = malloc(c1 * sizeof *v1);
    memcpy(i1, r1->index, c1 * sizeof *i1);
    memcpy(v1, r1->value, c1 * sizeof *v1);
    il_ff_compute_row(ff, w, 40);
    const il_ff_row *r2 = il_ff_compute_row(ff, w2, 17);
    CHECK(r2->count == c1 && memcmp(i1, r2->index, c1 * sizeof *i1) == 0 &&
          memcmp(v1, r2->value, c1 * sizeof *v1) == 0);
    r2 = il_ff_compute_row(ff, w, 17);
    CHECK(r2->count == c1 && memcmp(v1, r2->value, c1 * sizeof *v1) == 0);
    /* Out of range: an empty row. */
    CHECK(il_ff_compute_row(ff, w, n)->count == 0);
    printf("closed box (%s): worst |row sum - 1| %.2e, reciprocity %.2e (worst pair %.2f sigma), "
           "worst |F - point analytic| %.2e\n", method == IL_FF_HEMICUBE ? "hemicube" : "ray-cast",
           worst_sum, diff / total, worst, worst_point);
    free(i1);
    free(v1);
    free(F);
    il_ff_work_release(w);
    il_ff_work_release(w2);
    il_ff_release(ff);
    free_mesh(m);
}

static void test_cache(void)
{
    il_error err;
    il_ff_cache *c = NULL;
    enum { N = 100, LEN = 50 };
    size_t cap = 10000;
    CHECK_OK(il_ff_cache_create(N, cap, &c, &err), &err);
    uint32_t idx[LEN];
    float val[LEN];
    for (int k = 0; k < LEN; k++) {
        idx[k] = (uint32_t)(2 * k);
        val[k] = 0.01f * (float)k;
    }
    il_ff_row row = {LEN, idx, val};
    uint32_t stored = 0;
    bool failed = false;
    for (uint32_t i = 0; i < N; i++) {
        val[0] = (float)i;
        bool ok = il_ff_cache_put(c, i, &row);
        CHECK(il_ff_cache_bytes(c) <= cap);
        if (ok) {
            CHECK(!failed); /* rows are the same size: once full, always full */
            stored++;
        } else {
            failed = true;
            CHECK(il_ff_cache_get(c, i) == NULL);
        }
    }
    /* 400 bytes of data per row plus overhead: fewer than 25 fit, but some do. */
    CHECK(stored > 10 && stored < 25);
    CHECK(failed);
    for (uint32_t i = 0; i < N; i++) {
        const il_ff_row *r = il_ff_cache_get(c, i);
        if (i < stored) {
            CHECK(r && r->count == LEN && r->value[0] == (float)i && r->index[LEN - 1] == 2 * (LEN - 1) &&
                  r->value[LEN - 1] == val[LEN - 1]);
        } else {
            CHECK(r == NULL);
        }
    }
    /* Putting an existing row again succeeds without growing. */
    size_t before = il_ff_cache_bytes(c);
    CHECK(il_ff_cache_put(c, 0, &row));
    CHECK(il_ff_cache_bytes(c) == before);
    /* Empty rows are cached too; out of range is refused. */
    il_ff_row empty = {0, NULL, NULL};
    il_ff_cache_release(c);
    CHECK_OK(il_ff_cache_create(N, 1 << 20, &c, &err), &err);
    CHECK(il_ff_cache_put(c, 5, &empty));
    CHECK(il_ff_cache_get(c, 5) && il_ff_cache_get(c, 5)->count == 0);
    CHECK(!il_ff_cache_put(c, N, &row));
    CHECK(il_ff_cache_get(c, N) == NULL);
    il_ff_cache_release(c);
    /* A zero cap stores nothing. */
    CHECK_OK(il_ff_cache_create(N, 0, &c, &err), &err);
    CHECK(!il_ff_cache_put(c, 1, &row) && il_ff_cache_get(c, 1) == NULL && il_ff_cache_bytes(c) == 0);
    il_ff_cache_release(c);
}

/* Through the public scene API and il_patch_mesh_build: a closed 2 x 2 x 2 box
 * (walls facing in) with a mirror panel inside, which gets no patches but
 * occludes in both back-ends.  Without the panel every row sums to 1; with
 * it the rows lose what the panel hides, and the two back-ends agree. */
static il_scene *box_scene(bool mirror)
{
    il_error err;
    il_scene *scene = NULL;
    CHECK_OK(il_scene_create(&scene, &err), &err);
    /* Corners of [-1,1]^3 and 12 inward-facing triangles. */
    float p[24];
    for (int k = 0; k < 8; k++) {
        p[3 * k] = (k & 1) ? 1.0f : -1.0f;
        p[3 * k + 1] = (k & 2) ? 1.0f : -1.0f;
        p[3 * k + 2] = (k & 4) ? 1.0f : -1.0f;
    }
    static const uint32_t idx[36] = {0, 1, 3, 0, 3, 2,  4, 6, 7, 4, 7, 5,  0, 4, 5, 0, 5, 1,
                                     2, 3, 7, 2, 7, 6,  0, 2, 6, 0, 6, 4,  1, 5, 7, 1, 7, 3};
    il_mesh_desc md = {.name = "box", .num_vertices = 8, .num_triangles = 12, .positions = p,
                       .indices = idx, .material = 0};
    CHECK_OK(il_scene_add_mesh(scene, &md, &err), &err);
    if (mirror) {
        il_material_desc mat = {.name = "mirror", .type = IL_MATERIAL_MIRROR};
        uint32_t mi = 0;
        CHECK_OK(il_scene_add_material(scene, &mat, &mi, &err), &err);
        float q[12] = {-0.5f, -0.5f, 0.0f, 0.5f, -0.5f, 0.0f, 0.5f, 0.5f, 0.0f, -0.5f, 0.5f, 0.0f};
        static const uint32_t qi[6] = {0, 1, 2, 0, 2, 3};
        il_mesh_desc pd = {.name = "panel", .num_vertices = 4, .num_triangles = 2, .positions = q,
                           .indices = qi, .material = mi};
        CHECK_OK(il_scene_add_mesh(scene, &pd, &err), &err);
    }
    /* A light only because a scene needs one; form factors ignore it. */
    il_light_desc light = {.type = IL_LIGHT_POINT, .position = v3(0.2f, 0.7f, 0.3f),
                           .intensity = v3s(1.0f)};
    CHECK_OK(il_scene_add_light(scene, &light, &err), &err);
    CHECK_OK(il_scene_commit(scene, &err), &err);
    return scene;
}

static void test_scene_box(void)
{
    il_error err;
    for (int mirror = 0; mirror < 2; mirror++) {
        il_scene *scene = box_scene(mirror);
        il_rad_settings s;
        memset(&s, 0, sizeof s);
        s.subdivisions = 3;
        s.hemicube_resolution = 128;
        s.ray_samples = 1u << 14;
        s.seed = 11;
        s.threads = 1;
        il_patch_mesh *m = NULL;
        CHECK_OK(il_patch_mesh_build(scene, &(il_patch_sizing){s.patch_size, s.subdivisions}, &m, &err), &err);
        if (!m) {
            il_scene_release(scene);
            continue;
        }
        uint32_t n = m->num_patches;
        CHECK(n >= 6 * 16);
        double *sums[2] = {calloc(n, sizeof(double)), calloc(n, sizeof(double))};
        bool formed = true;
        for (int b = 0; b < 2; b++) {
            s.form_factors = b ? IL_FF_RAYCAST : IL_FF_HEMICUBE;
            il_ff *ff = NULL;
            il_ff_work *w = NULL;
            CHECK_OK(il_ff_create(m, &s, &ff, &err), &err);
            CHECK_OK(il_ff_work_create(ff, &w, &err), &err);
            for (uint32_t i = 0; ff && w && i < n; i++) {
                const il_ff_row *r = il_ff_compute_row(ff, w, i);
                formed &= row_well_formed(r, i, n);
                sums[b][i] = row_sum(r, 0, n);
            }
            il_ff_work_release(w);
            il_ff_release(ff);
        }
        CHECK(formed);
        double worst_one = 0.0, worst_agree = 0.0, least = 1.0;
        for (uint32_t i = 0; i < n; i++) {
            worst_one = fmax(worst_one, fmax(fabs(sums[0][i] - 1), fabs(sums[1][i] - 1)));
            worst_agree = fmax(worst_agree, fabs(sums[0][i] - sums[1][i]));
            least = fmin(least, sums[1][i]);
        }
        if (!mirror) {
            CHECK(worst_one < 0.01);
        } else {
            CHECK(least < 0.9);       /* the panel does hide part of the box */
            CHECK(worst_agree < 0.02); /* and both back-ends see it alike */
        }
        printf("scene box%s: %u patches, worst |sum - 1| %.2e, worst back-end disagreement %.2e\n",
               mirror ? " + mirror" : "", n, worst_one, worst_agree);
        free(sums[0]);
        free(sums[1]);
        il_patch_mesh_release(m);
        il_scene_release(scene);
    }
}

int main(void)
{
    test_point_polygon();
    test_area_to_area_analytic();
    test_cache();
    test_ray_closed_forms();
    test_hemicube_closed_forms();
    test_closed_box(IL_FF_RAYCAST, 0.02);
    test_closed_box(IL_FF_HEMICUBE, 0.03);
    test_scene_box();
    return check_report();
}
