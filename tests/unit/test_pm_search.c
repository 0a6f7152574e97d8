/* The photon map's search structures (pm_kdtree.c, pm_grid.c, pm_map.c)
 * against brute force: the kd-tree's k nearest are exactly the brute-force
 * k nearest (up to ties at the k-th distance), range queries return exactly
 * the photons within the radius for both structures, and a kd-tree and a
 * grid over the same photons return the same sets.  Data: uniform,
 * clustered, heavy duplicates, a lattice with photons exactly on the query
 * sphere and on cell boundaries, far-off coordinates with a tiny radius,
 * and n = 0, 1, 2, 1000, 100k. */
#include <stdlib.h>
#include <string.h>

#include "check.h"
#include "core/rng.h"
#include "methods/photon/pm_internal.h"

/* Photons carry their original index in `power` (the search never reads
 * it), so sets can be compared across structures that reorder them. */
static il_photon make_ph(float x, float y, float z, uint32_t id)
{
    il_photon ph = il_photon_pack(v3(x, y, z), v3s(1.0f), v3(0, 0, 1), v3(0, 0, 1));
    ph.power = id;
    return ph;
}

typedef enum { UNIFORM, CLUSTERED, DUPLICATES, LATTICE, FAR_OFF, PLANAR } dist_kind;

static il_photon *make_set(dist_kind kind, size_t n, uint64_t seed)
{
    il_photon *a = malloc((n ? n : 1) * sizeof *a);
    il_pcg32 r = il_pcg32_seed(seed, 11);
    il_vec3 centres[8];
    for (int c = 0; c < 8; c++)
        centres[c] = v3(il_pcg32_float(&r), il_pcg32_float(&r), il_pcg32_float(&r));
    for (size_t i = 0; i < n; i++) {
        float x = il_pcg32_float(&r), y = il_pcg32_float(&r), z = il_pcg32_float(&r);
        switch (kind) {
        case UNIFORM: break;
        case CLUSTERED: {
            il_vec3 c = centres[il_pcg32_next(&r) % 8];
            x = c.x + 0.02f * (x - 0.5f) * (x - 0.5f);
            y = c.y + 0.02f * (y - 0.5f);
            z = c.z + 0.001f * (z - 0.5f);
            break;
        }
        case DUPLICATES: { /* 37 distinct positions, some on a shared plane */
            uint32_t j = il_pcg32_next(&r) % 37;
            x = (float)(j % 5) * 0.25f;
            y = (float)(j / 5) * 0.125f;
            z = j < 20 ? 0.5f : 0.25f;
            break;
        }
        case LATTICE: /* multiples of 0.125: exactly representable, on cell walls */
            x = (float)(il_pcg32_next(&r) % 9) * 0.125f;
            y = (float)(il_pcg32_next(&r) % 9) * 0.125f;
            z = (float)(il_pcg32_next(&r) % 3) * 0.125f;
            break;
        case FAR_OFF: /* far from the origin, tiny spacing */
            x = 1000.0f + 0.01f * x;
            y = -2000.0f + 0.01f * y;
            z = 500.0f;
            break;
        case PLANAR: /* a Cornell-box wall: all on x = 0 */
            x = 0.0f;
            break;
        }
        a[i] = make_ph(x, y, z, (uint32_t)i);
    }
    return a;
}

static il_photon *copy_set(const il_photon *a, size_t n)
{
    il_photon *b = malloc((n ? n : 1) * sizeof *b);
    memcpy(b, a, n * sizeof *b);
    return b;
}

static int cmp_float(const void *a, const void *b)
{
    float x = *(const float *)a, y = *(const float *)b;
    return (x > y) - (x < y);
}
static int cmp_u32(const void *a, const void *b)
{
    uint32_t x = *(const uint32_t *)a, y = *(const uint32_t *)b;
    return (x > y) - (x < y);
}

/* A query point: random in (or a little beyond) the data's box, or exactly
 * on a photon. */
static il_vec3 query_point(il_pcg32 *r, const il_pm_map *m, int i)
{
    if (m->count > 0 && i % 3 == 0)
        return il_photon_pos(&m->photons[il_pcg32_next(r) % m->count]);
    il_vec3 lo = v3s(0.0f), hi = v3s(1.0f);
    if (m->count > 0) {
        lo = hi = il_photon_pos(&m->photons[0]);
        for (size_t j = 1; j < m->count; j++) {
            lo = v3_min(lo, il_photon_pos(&m->photons[j]));
            hi = v3_max(hi, il_photon_pos(&m->photons[j]));
        }
    }
    il_vec3 ext = v3_add(v3_sub(hi, lo), v3s(0.01f));
    return v3(lo.x + ext.x * (1.2f * il_pcg32_float(r) - 0.1f), lo.y + ext.y * (1.2f * il_pcg32_float(r) - 0.1f),
              lo.z + ext.z * (1.2f * il_pcg32_float(r) - 0.1f));
}

/* Brute force k nearest within max_d2 over m's photons (in m's order): the
 * sorted distances of the k nearest. */
static uint32_t brute_knn(const il_pm_map *m, il_vec3 p, uint32_t k, float max_d2, float *d2s)
{
    const float q[3] = {p.x, p.y, p.z};
    uint32_t c = 0;
    for (size_t i = 0; i < m->count; i++) {
        float d2 = il_pm_dist2(&m->photons[i], q);
        if (d2 <= max_d2)
            d2s[c++] = d2;
    }
    qsort(d2s, c, sizeof *d2s, cmp_float);
    return c < k ? c : k;
}

/* Checks one k-NN answer against brute force: the right count, distinct
 * photons, their true distances, and the same sorted distances as the
 * brute-force k nearest (so the same set up to ties at the k-th). */
static void check_knn(const il_pm_map *m, il_vec3 p, uint32_t k, float max_d2, float *bf, float *got,
                      il_pm_neighbour *out, uint32_t *ids)
{
    const float q[3] = {p.x, p.y, p.z};
    float r2 = -1.0f;
    uint32_t n = il_pm_knn(m, p, k, max_d2, out, &r2);
    uint32_t nb = brute_knn(m, p, k, max_d2, bf);
    CHECK(n == nb);
    if (n != nb)
        return;
    bool d2_ok = true, same = true, unique = true;
    for (uint32_t i = 0; i < n; i++) {
        if (out[i].index >= m->count || il_pm_dist2(&m->photons[out[i].index], q) != out[i].d2) {
            d2_ok = false;
            break;
        }
        got[i] = out[i].d2;
        ids[i] = out[i].index;
    }
    CHECK(d2_ok);
    if (!d2_ok)
        return;
    qsort(got, n, sizeof *got, cmp_float);
    qsort(ids, n, sizeof *ids, cmp_u32);
    for (uint32_t i = 0; i < n; i++) {
        same = same && got[i] == bf[i];
        unique = unique && (i == 0 || ids[i] != ids[i - 1]);
    }
    CHECK(same);
    CHECK(unique);
    CHECK(r2 == (n == k && k > 0 ? bf[k - 1] : max_d2));
}

/* The sorted original ids of the photons within d2 of p, by brute force or
 * by the map's range query. */
static uint32_t brute_range(const il_pm_map *m, il_vec3 p, float d2, uint32_t *ids)
{
    const float q[3] = {p.x, p.y, p.z};
    uint32_t c = 0;
    for (size_t i = 0; i < m->count; i++)
        if (il_pm_dist2(&m->photons[i], q) <= d2)
            ids[c++] = m->photons[i].power;
    qsort(ids, c, sizeof *ids, cmp_u32);
    return c;
}
static uint32_t map_range(const il_pm_map *m, il_vec3 p, float d2, uint32_t *ids, il_pm_buffer *buf)
{
    il_error err;
    buf->count = 0;
    CHECK_OK(il_pm_range(m, p, d2, buf, &err), &err);
    const float q[3] = {p.x, p.y, p.z};
    bool ok = true;
    for (uint32_t i = 0; i < buf->count; i++) {
        ids[i] = m->photons[buf->items[i].index].power;
        ok = ok && il_pm_dist2(&m->photons[buf->items[i].index], q) == buf->items[i].d2;
    }
    CHECK(ok);
    qsort(ids, buf->count, sizeof *ids, cmp_u32);
    return buf->count;
}

static bool same_ids(const uint32_t *a, uint32_t na, const uint32_t *b, uint32_t nb)
{
    return na == nb && (na == 0 || memcmp(a, b, na * sizeof *a) == 0);
}

/* The heap order's invariant: every node's left subtree is <= its split
 * value along its axis and its right subtree >=. */
static bool kd_valid(const il_photon *a, size_t n)
{
    for (size_t i = 0; i < n; i++) {
        unsigned ax = a[i].normal >> 14;
        if (ax > 2)
            return false;
        if (2 * i + 1 >= n)
            continue;
        /* walk the subtrees iteratively */
        size_t stack[64];
        int sp = 0;
        stack[sp++] = 2 * i + 1;
        while (sp) {
            size_t j = stack[--sp];
            if (a[j].p[ax] > a[i].p[ax])
                return false;
            if (2 * j + 1 < n) stack[sp++] = 2 * j + 1;
            if (2 * j + 2 < n) stack[sp++] = 2 * j + 2;
        }
        if (2 * i + 2 < n) {
            stack[sp++] = 2 * i + 2;
            while (sp) {
                size_t j = stack[--sp];
                if (a[j].p[ax] < a[i].p[ax])
                    return false;
                if (2 * j + 1 < n) stack[sp++] = 2 * j + 1;
                if (2 * j + 2 < n) stack[sp++] = 2 * j + 2;
            }
        }
        if (n > 5000 && i > 2000) /* the top of a big tree is enough */
            break;
    }
    return true;
}

static void run_case(dist_kind kind, size_t n, float radius, int queries, uint64_t seed)
{
    il_error err;
    il_photon *src = make_set(kind, n, seed);
    il_pm_map kd, grid;
    CHECK_OK(il_pm_map_build(&kd, copy_set(src, n), n, 1.0f, IL_PHOTON_KDTREE, 0.0f, &err), &err);
    CHECK_OK(il_pm_map_build(&grid, copy_set(src, n), n, 1.0f, IL_PHOTON_GRID, radius, &err), &err);
    CHECK(kd.count == n && grid.count == n);
    CHECK(kd_valid(kd.photons, kd.count));
    /* Both are permutations of the input. */
    uint32_t *ids = malloc((n + 1) * sizeof *ids), *ids2 = malloc((n + 1) * sizeof *ids2);
    for (size_t i = 0; i < n; i++) {
        ids[i] = kd.photons[i].power;
        ids2[i] = grid.photons[i].power;
    }
    qsort(ids, n, sizeof *ids, cmp_u32);
    qsort(ids2, n, sizeof *ids2, cmp_u32);
    bool perm = true;
    for (size_t i = 0; i < n; i++)
        perm = perm && ids[i] == i && ids2[i] == i;
    CHECK(perm);

    float *bf = malloc((n + 1) * sizeof *bf), *got = malloc((n + 1) * sizeof *got);
    uint32_t *ids3 = malloc((n + 1) * sizeof *ids3);
    il_pm_neighbour *out = malloc((n + 101) * sizeof *out);
    il_pm_buffer buf = {0};
    il_pcg32 r = il_pcg32_seed(seed, 99);
    const uint32_t ks[] = {1, 2, 7, 50, 100};
    for (int qi = 0; qi < queries; qi++) {
        il_vec3 p = query_point(&r, &kd, qi);
        uint32_t k = ks[qi % 5];
        float max_d2 = (qi % 4 == 0) ? INFINITY : radius * radius * (qi % 2 ? 1.0f : 9.0f);
        check_knn(&kd, p, k, max_d2, bf, got, out, ids);
        if (qi % 4 != 0)   /* the grid's k-NN, within a few cells */
            check_knn(&grid, p, k, max_d2, bf, got, out, ids);
        /* Range: the build radius, a smaller one and one spanning 3 cells. */
        const float d2s[3] = {radius * radius, 0.3f * radius * radius, 6.0f * radius * radius};
        for (int j = 0; j < 3; j++) {
            uint32_t nb = brute_range(&kd, p, d2s[j], ids);
            uint32_t nk = map_range(&kd, p, d2s[j], ids2, &buf);
            uint32_t ng = map_range(&grid, p, d2s[j], ids3, &buf);
            CHECK(same_ids(ids, nb, ids2, nk));
            CHECK(same_ids(ids, nb, ids3, ng));
        }
    }
    il_pm_buffer_free(&buf);
    free(bf);
    free(got);
    free(ids);
    free(ids2);
    free(ids3);
    free(out);
    free(src);
    il_pm_map_free(&kd);
    il_pm_map_free(&grid);
}

static void test_edges(void)
{
    il_error err;
    il_pm_map m;
    /* Empty maps: every query finds nothing. */
    for (int s = 0; s < 2; s++) {
        CHECK_OK(il_pm_map_build(&m, NULL, 0, 1.0f, s ? IL_PHOTON_GRID : IL_PHOTON_KDTREE, 0.1f, &err), &err);
        il_pm_neighbour out[4];
        float r2 = 0.0f;
        CHECK(il_pm_knn(&m, v3s(0.0f), 4, 1.0f, out, &r2) == 0);
        CHECK(r2 == 1.0f);
        il_pm_buffer b = {0};
        CHECK_OK(il_pm_range(&m, v3s(0.0f), 1.0f, &b, &err), &err);
        CHECK(b.count == 0);
        CHECK(il_pm_map_bytes(&m) <= 16);
        il_pm_map_free(&m);
    }
    /* Bad input fails cleanly and frees the photons (the map owns them). */
    il_photon *a = make_set(UNIFORM, 10, 1);
    a[3].p[1] = NAN;
    CHECK(il_pm_map_build(&m, a, 10, 1.0f, IL_PHOTON_KDTREE, 0.0f, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "photon 3") != NULL);
    CHECK(m.photons == NULL && m.count == 0);
    a = make_set(UNIFORM, 10, 1);
    CHECK(il_pm_map_build(&m, a, 10, 1.0f, IL_PHOTON_GRID, 0.0f, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "radius") != NULL);
    /* Memory: 20 bytes a photon, plus 4 a bucket for the grid. */
    a = make_set(UNIFORM, 1000, 1);
    CHECK_OK(il_pm_map_build(&m, a, 1000, 1.0f, IL_PHOTON_KDTREE, 0.0f, &err), &err);
    CHECK(il_pm_map_bytes(&m) == 20000);
    il_pm_map_free(&m);
    a = make_set(UNIFORM, 1000, 1);
    CHECK_OK(il_pm_map_build(&m, a, 1000, 1.0f, IL_PHOTON_GRID, 0.05f, &err), &err);
    CHECK(il_pm_map_bytes(&m) == 20000 + 4 * (1024 + 1));
    /* A query point far away, or NaN, finds nothing and does not crash. */
    il_pm_buffer b = {0};
    CHECK_OK(il_pm_range(&m, v3(1e30f, -1e30f, 0.0f), 0.0025f, &b, &err), &err);
    CHECK_OK(il_pm_range(&m, v3(NAN, 0.0f, 0.0f), 0.0025f, &b, &err), &err);
    CHECK(b.count == 0);
    il_pm_buffer_free(&b);
    il_pm_map_free(&m);
    /* A huge extent with a tiny radius: the grid widens its cells and still
     * answers exactly (checked in run_case's FAR_OFF with a small radius). */
    a = malloc(3 * sizeof *a);
    a[0] = make_ph(-1e7f, 0.0f, 0.0f, 0);
    a[1] = make_ph(1e7f, 0.0f, 0.0f, 1);
    a[2] = make_ph(1e7f, 1e-4f, 0.0f, 2);
    CHECK_OK(il_pm_map_build(&m, a, 3, 1.0f, IL_PHOTON_GRID, 1e-4f, &err), &err);
    CHECK(m.cell_size > 1e-4f);
    b = (il_pm_buffer){0};
    CHECK_OK(il_pm_range(&m, v3(1e7f, 0.0f, 0.0f), 1e-8f, &b, &err), &err);
    CHECK(b.count == 2);
    il_pm_buffer_free(&b);
    il_pm_map_free(&m);
}

int main(void)
{
    test_edges();
    /* 30 and 64: tables of 32 and 64 buckets for 27 cells, many collisions. */
    const size_t sizes[] = {0, 1, 2, 3, 7, 30, 64, 1000};
    for (size_t i = 0; i < sizeof sizes / sizeof *sizes; i++)
        for (int kind = UNIFORM; kind <= PLANAR; kind++)
            run_case((dist_kind)kind, sizes[i], 0.05f, 60, 100 + i);
    run_case(LATTICE, 1000, 0.125f, 200, 7);      /* photons exactly on the sphere */
    run_case(LATTICE, 1000, 0.25f, 200, 8);
    run_case(DUPLICATES, 20000, 0.1f, 100, 9);
    run_case(FAR_OFF, 10000, 0.0003f, 200, 10);
    run_case(UNIFORM, 100000, 0.02f, 150, 11);
    run_case(CLUSTERED, 100000, 0.002f, 150, 12);
    run_case(PLANAR, 100000, 0.01f, 150, 13);
    return check_report();
}
