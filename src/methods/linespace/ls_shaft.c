/* Shaft indexing of a Linespace (Keul, Lemke & Mueller 2016, sec. 3; Nilles
 * 2017, sec. 3.1): faces, patches, the shaft of a pair of patches, and the
 * shaft a line runs through. */
#include <math.h>

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

/* The patch of face f holding point q (on the face), clamped to the face;
 * scale = n / size per axis. */
static inline uint32_t patch_of(il_vec3 lo, il_vec3 scale, uint32_t n, uint32_t f, il_vec3 q)
{
    int u, v;
    face_axes(f, &u, &v);
    float fu = (v3_get(q, u) - v3_get(lo, u)) * v3_get(scale, u);
    float fv = (v3_get(q, v) - v3_get(lo, v)) * v3_get(scale, v);
    int iu = (int)fu, iv = (int)fv;   /* truncation: the clamp below handles q < lo */
    iu = fu < 0.0f ? 0 : (iu >= (int)n ? (int)n - 1 : iu);
    iv = fv < 0.0f ? 0 : (iv >= (int)n ? (int)n - 1 : iv);
    return (uint32_t)iu * n + (uint32_t)iv;
}

bool il_ls_locate(il_vec3 lo, il_vec3 size, uint32_t n, il_vec3 p, il_vec3 d, uint32_t *face_in,
                  uint32_t *patch_in, uint32_t *face_out, uint32_t *patch_out, float *t_in,
                  float *t_out)
{
    float tn = -INFINITY, tf = INFINITY;
    int an = -1, af = -1;
    for (int i = 0; i < 3; i++) {
        float di = v3_get(d, i);
        if (di == 0.0f)
            continue;       /* parallel to the slab: it never bounds the line */
        float inv = 1.0f / di;
        float l = v3_get(lo, i), h = l + v3_get(size, i), pi = v3_get(p, i);
        float t1 = (l - pi) * inv, t2 = (h - pi) * inv;
        float near = di > 0.0f ? t1 : t2, far = di > 0.0f ? t2 : t1;
        if (near > tn) {
            tn = near;
            an = i;
        }
        if (far < tf) {
            tf = far;
            af = i;
        }
    }
    if (an < 0 || af < 0)
        return false;
    /* It enters through the low side of an axis it travels up, and leaves
     * through the high side; opposite when it travels down. */
    uint32_t fi = 2u * (uint32_t)an + (v3_get(d, an) > 0.0f ? 0u : 1u);
    uint32_t fo = 2u * (uint32_t)af + (v3_get(d, af) > 0.0f ? 1u : 0u);
    il_vec3 scale = v3((float)n / size.x, (float)n / size.y, (float)n / size.z);
    *face_in = fi;
    *face_out = fo;
    *patch_in = patch_of(lo, scale, n, fi, v3_fma(p, d, tn));
    *patch_out = patch_of(lo, scale, n, fo, v3_fma(p, d, tf));
    *t_in = tn;
    *t_out = tf;
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
