/* Shaft indexing of a Linespace (Keul, Lemke & Mueller 2016, sec. 3; Nilles
 * 2017, sec. 3.1): faces, patches, the shaft of a pair of patches, and the
 * shaft a line runs through. */
#include <math.h>
#if defined(__SSE2__)
#include <immintrin.h>
#endif

#include "methods/linespace/ls.h"

/* The two axes spanning face f, in increasing order. */
static inline void face_axes(uint32_t f, int *u, int *v)
{
    int a = (int)(f / 2u);
    *u = a == 0 ? 1 : 0;
    *v = a == 2 ? 1 : 2;
}

uint32_t il_ls_face_pair(uint32_t fa, uint32_t fb)
{
    /* Pairs starting with a face below fa: sum over f < fa of (5 - f). */
    return 5u * fa - fa * (fa - 1u) / 2u + (fb - fa - 1u);
}

uint32_t il_ls_shaft_index(uint32_t n, uint32_t fa, uint32_t pa, uint32_t fb, uint32_t pb,
                           uint32_t *dir)
{
    uint32_t n2 = n * n;
    if (fa < fb) {
        *dir = 0u;
        return il_ls_face_pair(fa, fb) * n2 * n2 + pa * n2 + pb;
    }
    *dir = 1u;
    return il_ls_face_pair(fb, fa) * n2 * n2 + pb * n2 + pa;
}

void il_ls_shaft_patches(uint32_t n, uint32_t shaft, uint32_t *fa, uint32_t *pa, uint32_t *fb,
                         uint32_t *pb)
{
    uint32_t n2 = n * n, n4 = n2 * n2;
    uint32_t pair = shaft / n4, rest = shaft % n4;
    uint32_t a = 0;
    while (pair >= 5u - a) {
        pair -= 5u - a;
        a++;
    }
    *fa = a;
    *fb = a + 1u + pair;
    *pa = rest / n2;
    *pb = rest % n2;
}

uint32_t il_ls_coarse_n(uint32_t n)
{
    for (uint32_t f = 2; f <= n; f++)
        if (n % f == 0)
            return n / f;
    return 0;
}

uint32_t il_ls_coarse_shaft(uint32_t n, uint32_t shaft)
{
    uint32_t nc = il_ls_coarse_n(n), k = n / nc, fa, pa, fb, pb, dir;
    il_ls_shaft_patches(n, shaft, &fa, &pa, &fb, &pb);
    /* Patch (i, j) of N lies in patch (i / k, j / k) of N_c = N / k. */
    uint32_t ca = (pa / n / k) * nc + (pa % n) / k, cb = (pb / n / k) * nc + (pb % n) / k;
    return il_ls_shaft_index(nc, fa, ca, fb, cb, &dir); /* fa < fb: dir 0, as the shaft's own */
}

/* The second and third axes of a face on axis a (the two spanning it, in
 * increasing order), by table rather than by branches. */
static const uint8_t face_u[3] = {1, 0, 0}, face_v[3] = {2, 2, 1};

/* The patch holding the point whose voxel-local coordinates, in patch
 * units, are f[] (f = (q - lo) n / size), on a face on axis a, clamped to
 * the face: min(max(f, 0), n - 1) truncated is the truncation of f clamped
 * to 0..n-1, without branches. */
static inline uint32_t patch_of(const float f[3], uint32_t a, uint32_t n)
{
    float top = (float)(n - 1u);
    float fu = f[face_u[a]], fv = f[face_v[a]];
    fu = fu > 0.0f ? fu : 0.0f;
    fv = fv > 0.0f ? fv : 0.0f;
    fu = fu < top ? fu : top;
    fv = fv < top ? fv : top;
    return (uint32_t)fu * n + (uint32_t)fv;
}

/* il_ls_locate on arrays, the scale n / size given: the slab method with
 * selects where the branches would follow the random direction. */
static inline bool locate(const float lo[3], const float size[3], const float scale[3], uint32_t n,
                          const float p[3], const float d[3], uint32_t *face_in, uint32_t *patch_in,
                          uint32_t *face_out, uint32_t *patch_out, float *t_in, float *t_out)
{
    float tn = -INFINITY, tf = INFINITY;
    int an = -1, af = -1;
    for (int i = 0; i < 3; i++) {
        float di = d[i];
        float inv = 1.0f / di;
        float l = lo[i], h = l + size[i];
        float t1 = (l - p[i]) * inv, t2 = (h - p[i]) * inv;
        bool up = di > 0.0f;
        float near = up ? t1 : t2, far = up ? t2 : t1;
        /* Parallel to the slab: it never bounds the line. */
        near = di == 0.0f ? -INFINITY : near;
        far = di == 0.0f ? INFINITY : far;
        bool closer = near > tn, sooner = far < tf;
        an = closer ? i : an;
        tn = closer ? near : tn;
        af = sooner ? i : af;
        tf = sooner ? far : tf;
    }
    if (an < 0 || af < 0)
        return false;
    /* It enters through the low side of an axis it travels up, and leaves
     * through the high side; opposite when it travels down. */
    *face_in = 2u * (uint32_t)an + (d[an] > 0.0f ? 0u : 1u);
    *face_out = 2u * (uint32_t)af + (d[af] > 0.0f ? 1u : 0u);
    float fin[3], fout[3];
    for (int i = 0; i < 3; i++) {
        fin[i] = (p[i] + d[i] * tn - lo[i]) * scale[i];
        fout[i] = (p[i] + d[i] * tf - lo[i]) * scale[i];
    }
    *patch_in = patch_of(fin, (uint32_t)an, n);
    *patch_out = patch_of(fout, (uint32_t)af, n);
    *t_in = tn;
    *t_out = tf;
    return true;
}

bool il_ls_locate(il_vec3 lo, il_vec3 size, uint32_t n, il_vec3 p, il_vec3 d, uint32_t *face_in,
                  uint32_t *patch_in, uint32_t *face_out, uint32_t *patch_out, float *t_in,
                  float *t_out)
{
    const float l[3] = {lo.x, lo.y, lo.z}, s[3] = {size.x, size.y, size.z},
                sc[3] = {(float)n / size.x, (float)n / size.y, (float)n / size.z},
                pp[3] = {p.x, p.y, p.z}, dd[3] = {d.x, d.y, d.z};
    return locate(l, s, sc, n, pp, dd, face_in, patch_in, face_out, patch_out, t_in, t_out);
}

/* il_ls_face_pair of every ordered pair of different faces, either order. */
static const uint8_t pair_of[6][6] = {
    {0, 0, 1, 2, 3, 4},    {0, 0, 5, 6, 7, 8},     {1, 5, 0, 9, 10, 11},
    {2, 6, 9, 0, 12, 13},  {3, 7, 10, 12, 0, 14},  {4, 8, 11, 13, 14, 0},
};

#if defined(__SSE2__)
/* m ? a : b, lane by lane. */
static inline __m128 select_ps(__m128 m, __m128 a, __m128 b)
{
    return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b));
}

/* locate on the three axes at once (lane 3 unused, its direction 0): the
 * same operations lane by lane, so the same numbers.  The entry axis is
 * the first lane holding the largest entry distance (the scalar loop keeps
 * the first of equals), the exit axis the first holding the smallest exit
 * distance; a parallel or NaN lane never bounds the line. */
static inline bool locate_sse(__m128 lo, __m128 size, __m128 scale, uint32_t n, __m128 p, __m128 d,
                              uint32_t *face_in, uint32_t *patch_in, uint32_t *face_out,
                              uint32_t *patch_out, float *t_in, float *t_out)
{
    const __m128 zero = _mm_setzero_ps(), inf = _mm_set1_ps(INFINITY), ninf = _mm_set1_ps(-INFINITY);
    __m128 inv = _mm_div_ps(_mm_set1_ps(1.0f), d);
    __m128 t1 = _mm_mul_ps(_mm_sub_ps(lo, p), inv);
    __m128 t2 = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(lo, size), p), inv);
    __m128 up = _mm_cmpgt_ps(d, zero);
    __m128 near = select_ps(up, t1, t2), far = select_ps(up, t2, t1);
    __m128 still = _mm_or_ps(_mm_cmpeq_ps(d, zero), _mm_cmpunord_ps(d, d));
    near = select_ps(_mm_or_ps(still, _mm_cmpunord_ps(near, near)), ninf, near);
    far = select_ps(_mm_or_ps(still, _mm_cmpunord_ps(far, far)), inf, far);
    __m128 mx = _mm_max_ps(near, _mm_shuffle_ps(near, near, _MM_SHUFFLE(2, 3, 0, 1)));
    mx = _mm_max_ps(mx, _mm_shuffle_ps(mx, mx, _MM_SHUFFLE(1, 0, 3, 2)));
    __m128 mn = _mm_min_ps(far, _mm_shuffle_ps(far, far, _MM_SHUFFLE(2, 3, 0, 1)));
    mn = _mm_min_ps(mn, _mm_shuffle_ps(mn, mn, _MM_SHUFFLE(1, 0, 3, 2)));
    float tn = _mm_cvtss_f32(mx), tf = _mm_cvtss_f32(mn);
    if (!(tn > -INFINITY) || !(tf < INFINITY))
        return false;
    int an = __builtin_ctz((unsigned)_mm_movemask_ps(_mm_cmpeq_ps(near, mx)));
    int af = __builtin_ctz((unsigned)_mm_movemask_ps(_mm_cmpeq_ps(far, mn)));
    int ups = _mm_movemask_ps(up);
    *face_in = 2u * (uint32_t)an + ((ups >> an) & 1 ? 0u : 1u);
    *face_out = 2u * (uint32_t)af + ((ups >> af) & 1 ? 1u : 0u);
    const __m128 top = _mm_set1_ps((float)(n - 1u));
    __m128 fin = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(p, _mm_mul_ps(d, mx)), lo), scale);
    __m128 fout = _mm_mul_ps(_mm_sub_ps(_mm_add_ps(p, _mm_mul_ps(d, mn)), lo), scale);
    /* Clamped to 0..n-1, then truncated: patch_of. */
    int32_t ci[4], co[4];
    _mm_storeu_si128((__m128i *)ci, _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(fin, zero), top)));
    _mm_storeu_si128((__m128i *)co, _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(fout, zero), top)));
    *patch_in = (uint32_t)ci[face_u[an]] * n + (uint32_t)ci[face_v[an]];
    *patch_out = (uint32_t)co[face_u[af]] * n + (uint32_t)co[face_v[af]];
    *t_in = tn;
    *t_out = tf;
    return true;
}
#endif

bool il_ls_find(const il_linespace *ls, il_vec3 p, il_vec3 d, uint32_t *voxel, uint32_t *shaft,
                uint32_t *dir, float *t_in, float *t_out)
{
    uint32_t fi, pi, fo, po;
#if defined(__SSE2__)
    /* il_ls_cell_of and il_ls_cell_box on the three axes at once: the
     * truncation clamped to 0..res-1 is the truncation of x clamped to
     * 0..res-1 (x >= -1e-3 here). */
    const __m128 pv = _mm_setr_ps(p.x, p.y, p.z, 0.0f), glo = _mm_setr_ps(ls->lo.x, ls->lo.y, ls->lo.z, 0.0f);
    const __m128 size = _mm_setr_ps(ls->vsize.x, ls->vsize.y, ls->vsize.z, 0.0f);
    const __m128 res = _mm_setr_ps((float)ls->res[0], (float)ls->res[1], (float)ls->res[2], 1.0f);
    __m128 x = _mm_mul_ps(_mm_sub_ps(pv, glo), _mm_setr_ps(ls->inv_vsize.x, ls->inv_vsize.y, ls->inv_vsize.z, 0.0f));
    __m128 inside = _mm_and_ps(_mm_cmpge_ps(x, _mm_set1_ps(-1e-3f)),
                               _mm_cmple_ps(x, _mm_add_ps(res, _mm_set1_ps(1e-3f))));
    if ((_mm_movemask_ps(inside) & 7) != 7)
        return false;
    __m128i ci = _mm_cvttps_epi32(_mm_min_ps(_mm_max_ps(x, _mm_setzero_ps()), _mm_sub_ps(res, _mm_set1_ps(1.0f))));
    int32_t c[4];
    _mm_storeu_si128((__m128i *)c, ci);
    int32_t v = ls->cell[(uint32_t)c[0] + (size_t)ls->res[0] * ((uint32_t)c[1] + (size_t)ls->res[1] * (uint32_t)c[2])];
    if (v < 0)
        return false;
    __m128 lo = _mm_add_ps(glo, _mm_mul_ps(size, _mm_cvtepi32_ps(ci)));
    if (!locate_sse(lo, size, _mm_setr_ps(ls->patch_scale.x, ls->patch_scale.y, ls->patch_scale.z, 0.0f), ls->n,
                    pv, _mm_setr_ps(d.x, d.y, d.z, 0.0f), &fi, &pi, &fo, &po, t_in, t_out))
        return false;
#else
    uint32_t c[3];
    if (!il_ls_cell_of(ls, p, c))
        return false;
    int32_t v = ls->cell[c[0] + (size_t)ls->res[0] * (c[1] + (size_t)ls->res[1] * c[2])];
    if (v < 0)
        return false;
    il_vec3 lo;
    il_ls_cell_box(ls, c, &lo);
    const float l[3] = {lo.x, lo.y, lo.z}, s[3] = {ls->vsize.x, ls->vsize.y, ls->vsize.z},
                sc[3] = {ls->patch_scale.x, ls->patch_scale.y, ls->patch_scale.z},
                pp[3] = {p.x, p.y, p.z}, dd[3] = {d.x, d.y, d.z};
    if (!locate(l, s, sc, ls->n, pp, dd, &fi, &pi, &fo, &po, t_in, t_out))
        return false;
#endif
    /* il_ls_shaft_index: numbered from the lower face's patch. */
    uint32_t n2 = ls->n * ls->n;
    bool down = fi > fo;
    uint32_t pa = down ? po : pi, pb = down ? pi : po;
    *dir = down ? 1u : 0u;
    *shaft = (uint32_t)pair_of[fi][fo] * n2 * n2 + pa * n2 + pb;
    *voxel = (uint32_t)v;
    return true;
}

void il_ls_patch_corners(il_vec3 lo, il_vec3 size, uint32_t n, uint32_t face, uint32_t patch,
                         il_vec3 corners[4])
{
    int a = (int)(face / 2u), u, v;
    face_axes(face, &u, &v);
    float c[3];
    c[a] = v3_get(lo, a) + ((face & 1u) ? v3_get(size, a) : 0.0f);
    float su = v3_get(size, u) / (float)n, sv = v3_get(size, v) / (float)n;
    float u0 = v3_get(lo, u) + su * (float)(patch / n), v0 = v3_get(lo, v) + sv * (float)(patch % n);
    for (int k = 0; k < 4; k++) {
        c[u] = u0 + ((k & 1) ? su : 0.0f);
        c[v] = v0 + ((k & 2) ? sv : 0.0f);
        corners[k] = v3(c[0], c[1], c[2]);
    }
}

double il_ls_shaft_measures(il_vec3 size, uint32_t n, uint32_t k, float *out)
{
    const uint32_t ns = il_ls_num_shafts(n);
    const il_vec3 lo = v3s(0.0f);
    double total = 0.0;
    for (uint32_t s = 0; s < ns; s++) {
        uint32_t fa, pa, fb, pb;
        il_ls_shaft_patches(n, s, &fa, &pa, &fb, &pb);
        il_vec3 ca[4], cb[4];
        il_ls_patch_corners(lo, size, n, fa, pa, ca);
        il_ls_patch_corners(lo, size, n, fb, pb, cb);
        il_vec3 ea = v3_sub(ca[1], ca[0]), fa2 = v3_sub(ca[2], ca[0]);
        il_vec3 eb = v3_sub(cb[1], cb[0]), fb2 = v3_sub(cb[2], cb[0]);
        double area_a = v3_length(ea) * v3_length(fa2), area_b = v3_length(eb) * v3_length(fb2);
        int axa = (int)(fa / 2u), axb = (int)(fb / 2u);
        double sum = 0.0;
        for (uint32_t i = 0; i < k * k; i++) {
            float sa = ((float)(i / k) + 0.5f) / (float)k, ta = ((float)(i % k) + 0.5f) / (float)k;
            il_vec3 a = v3_fma(v3_fma(ca[0], ea, sa), fa2, ta);
            for (uint32_t j = 0; j < k * k; j++) {
                float sb = ((float)(j / k) + 0.5f) / (float)k, tb = ((float)(j % k) + 0.5f) / (float)k;
                il_vec3 b = v3_fma(v3_fma(cb[0], eb, sb), fb2, tb);
                il_vec3 w = v3_sub(b, a);
                double r2 = (double)v3_dot(w, w);
                if (!(r2 > 0.0))
                    continue;
                /* cos a cos b / r^2 (throughput) times the chord r. */
                double c = fabs((double)v3_get(w, axa)) * fabs((double)v3_get(w, axb));
                sum += c / (r2 * sqrt(r2));
            }
        }
        double m = sum * area_a * area_b / ((double)k * k * k * k);
        out[s] = (float)m;
        total += m;
    }
    double volume = (double)size.x * size.y * size.z;
    double scale = total > 0.0 ? 2.0 * IL_PI * volume / total : 1.0;
    for (uint32_t s = 0; s < ns; s++)
        out[s] = (float)(out[s] * scale);
    return total;
}
