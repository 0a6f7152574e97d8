/* Hemicube form factors (Cohen & Greenberg, "The Hemi-Cube: A Radiosity
 * Solution for Complex Environments", SIGGRAPH 1985; Cohen & Wallace 1993,
 * section 5.8).  A unit hemicube sits at the centre of patch i; every other
 * patch (and every mirror/glass triangle, as an occluder) is projected onto
 * its five faces with a depth buffer keeping the nearest item per pixel, and
 * F_ij is the sum of the delta form factors of the pixels that see j.
 *
 * Frame: the top face is the plane z = 1 of the patch frame (s, t, n) from
 * il_frame_from_normal (deterministic); pixels cover [-1,1]^2 at res x res.
 * The four side faces are x = +-1 and y = +-1 with z in [0,1], res x res/2.
 *
 * Delta form factors.  Cohen & Greenberg's midpoint values are
 *     top:  dF = dA / (pi (x^2 + y^2 + 1)^2),
 *     side: dF = z dA / (pi (y^2 + z^2 + 1)^2);
 * we store instead each pixel's exact form factor (Lambert's formula over the
 * pixel square, il_ff_point_polygon), which tends to the same values as the
 * pixels shrink but makes the table sum to 1 exactly at any resolution.
 * Symmetry: the top face repeats under the 8 reflections x<->-x, y<->-y,
 * x<->y, so one octant is stored (h(h+1)/2 values, h = res/2); the side faces
 * are identical and symmetric left-right, so one quadrant (h x h) serves all
 * four.  For the final sum each distinct pixel row also gets its running
 * sums over the folded columns (h+1 doubles), so a run of pixels with one id
 * costs two look-ups instead of one add per pixel.  At res 256: 97 KiB of
 * delta form factors and 258 KiB of running sums.
 *
 * Per row, cheap tests first: chunks of up to 64 consecutive patches of one
 * surface are skipped in one test when their bounding box lies behind the
 * hemicube's base plane, or when they are coplanar and the plane passes
 * through the centre (the shooter's own surface).  Per patch: skip when its
 * plane passes through the centre (edge-on, covers no pixel) or all corners
 * lie behind the base plane; a back face is drawn without an id (it receives
 * nothing but hides what lies behind it, as mirror/glass triangles do).  The
 * corners are classified once against the five faces; a polygon whose
 * corners all lie inside one face's frustum (the common case) is projected
 * and drawn directly, the others go through per-face outcodes and
 * Sutherland-Hodgman clipping against the planes some corner violates.
 * Scan conversion samples pixel centres on half-open spans (no pixel is
 * shared by two abutting polygons: each edge's line is evaluated from its
 * lower end, so both neighbours compute the same x), bounds each row by the
 * intersection of the edges' half-planes (the polygons are convex) and
 * interpolates 1/depth, which is affine in screen space for a plane.  Each
 * buffer row remembers the span it was written in, so the final sum and
 * the clearing touch only written pixels.
 *
 * With SSE2 the common path works four-wide: a polygon's four corners (a
 * triangle repeats its first) are transformed, classified and projected in
 * one register each, the span ends of four rows come out of one pass over
 * the edges, and pixels are depth-tested four at a time.  The plain C path
 * (IL_HC_NO_SIMD, or no SSE2) computes the same values, operation for
 * operation; both give the same rows. */
#include <math.h>
#include <stdlib.h>
#include <string.h>
/* SSE2 (every x86-64) for the four-wide paths; plain C elsewhere. */
#if defined(__SSE2__) && !defined(IL_HC_NO_SIMD)
#define IL_HC_SIMD 1
#include <emmintrin.h>
#else
#define IL_HC_SIMD 0
#endif

#include "core/error.h"
#include "methods/radiosity/rad_ff_internal.h"

#define IL_HC_MAX_VERTS 16
#define IL_HC_NONE UINT32_MAX
#define IL_HC_CHUNK 64u

/* One drawable item (a patch, or a mirror/glass triangle): its corners and
 * its unit plane normal (from the corners, facing its front). */
typedef struct il_hc_item {
    float x[4], y[4], z[4];  /* a triangle repeats its first corner */
    float n[3];
    uint32_t corners;
} il_hc_item;

/* Consecutive items of one surface: a bounding box and, when they all lie
 * in one plane n.x = d (within tol), that plane. */
typedef struct il_hc_chunk {
    uint32_t first, count;
    double lo[3], hi[3];
    double n[3], d, tol;
    bool planar;
} il_hc_chunk;

struct il_hemicube {
    const il_patch_mesh *mesh;
    uint32_t res, half;
    float *top;              /* octant: index hi*(hi+1)/2 + lo of the folded pixel */
    float *side;             /* quadrant: [row in z][folded column] */
    double *top_cum;         /* [folded row][m]: sum of the first m folded columns */
    double *side_cum;        /* [row in z][m], the same for the sides */
    uint32_t *fold;          /* res: pixel column/row -> distance from the centre line */
    il_hc_item *items;       /* patches 0..num_patches-1, then the occluders */
    uint32_t *item_id;       /* the patch, or IL_HC_NONE for an occluder */
    uint32_t num_items;
    il_hc_chunk *chunks;
    uint32_t num_chunks;
};

struct il_hemicube_buffers {
    const il_hemicube *hc;
    uint32_t *ids;           /* top res*res, then four sides res*half each: 3 res rows of res */
    float *depth;            /* 1/depth, 0 = empty */
    int32_t *span;           /* per buffer row: [lo, hi) written; lo >= hi when none */
    float *scratch;          /* num_patches tallies, kept zeroed */
    uint32_t *ids_mem;       /* the allocations behind ids and depth (padded) */
    float *depth_mem;
};

typedef struct { float a, b, d; } fvert;

static void chunk_close(il_hemicube *hc, il_hc_chunk *ch)
{
    /* Plane of the first item (double), then the worst distance of any corner. */
    const il_hc_item *it = &hc->items[ch->first];
    ch->n[0] = it->n[0], ch->n[1] = it->n[1], ch->n[2] = it->n[2];
    double len = sqrt(ch->n[0] * ch->n[0] + ch->n[1] * ch->n[1] + ch->n[2] * ch->n[2]);
    ch->planar = len > 0.5;
    if (!ch->planar)
        return;
    for (int a = 0; a < 3; a++)
        ch->n[a] /= len;
    ch->d = ch->n[0] * it->x[0] + ch->n[1] * it->y[0] + ch->n[2] * it->z[0];
    double tol = 0.0, mag = 0.0;
    for (uint32_t j = ch->first; j < ch->first + ch->count; j++) {
        for (uint32_t k = 0; k < hc->items[j].corners; k++) {
            const il_hc_item *q = &hc->items[j];
            double p[3] = {q->x[k], q->y[k], q->z[k]};
            tol = fmax(tol, fabs(ch->n[0] * p[0] + ch->n[1] * p[1] + ch->n[2] * p[2] - ch->d));
            mag = fmax(mag, fmax(fabs(p[0]), fmax(fabs(p[1]), fabs(p[2]))));
        }
    }
    /* Allow for the rounding of the float test against it. */
    ch->tol = tol + 4e-7 * mag;
}
/* A thin pane is not drawn: the hemicube cannot let a fraction of a pixel
 * through, and a clear pane passes nearly all (the ray-cast form factors
 * pass its transmittance, trace.c). */
static bool is_pane(const il_patch_mesh *mesh, uint32_t t)
{
    return mesh->tri_panes && mesh->tri_panes[t].ior > 0.0f;
}


static void build_items(il_hemicube *hc)
{
    const il_patch_mesh *mesh = hc->mesh;
    uint32_t n = 0;
    il_hc_chunk *ch = NULL;
    uint32_t prev_surface = UINT32_MAX;
    for (uint32_t t = 0, j = 0; j < mesh->num_patches || t < mesh->num_tris;) {
        il_hc_item *it = &hc->items[n];
        il_vec3 c[4];
        uint32_t surface;
        if (j < mesh->num_patches) {
            const il_patch *pa = &mesh->patches[j];
            it->corners = pa->num_corners == 4 ? 4 : 3;
            for (uint32_t k = 0; k < 4; k++)
                c[k] = mesh->positions[pa->v[k < it->corners ? k : 0]];
            hc->item_id[n] = j;
            surface = pa->surface;
            j++;
        } else {
            if (mesh->tri_patch[t] != IL_NO_PATCH || is_pane(mesh, t)) {
                t++;
                continue;
            }
            it->corners = 3;
            for (uint32_t k = 0; k < 4; k++)
                c[k] = mesh->positions[mesh->tri_indices[3 * (size_t)t + (k < 3 ? k : 0)]];
            hc->item_id[n] = IL_HC_NONE;
            surface = UINT32_MAX - 1; /* occluders: chunks by position in the list only */
            t++;
        }
        for (uint32_t k = 0; k < 4; k++) {
            it->x[k] = c[k].x;
            it->y[k] = c[k].y;
            it->z[k] = c[k].z;
        }
        il_vec3 nrm = it->corners == 4 ? v3_cross(v3_sub(c[2], c[0]), v3_sub(c[3], c[1]))
                                       : v3_cross(v3_sub(c[1], c[0]), v3_sub(c[2], c[0]));
        float len = v3_length(nrm);
        nrm = len > 0.0f ? v3_scale(nrm, 1.0f / len) : v3(0.0f, 0.0f, 0.0f);
        it->n[0] = nrm.x, it->n[1] = nrm.y, it->n[2] = nrm.z;

        if (!ch || surface != prev_surface || ch->count == IL_HC_CHUNK) {
            if (ch)
                chunk_close(hc, ch);
            ch = &hc->chunks[hc->num_chunks++];
            ch->first = n;
            ch->count = 0;
            for (int a = 0; a < 3; a++)
                ch->lo[a] = INFINITY, ch->hi[a] = -INFINITY;
        }
        prev_surface = surface;
        ch->count++;
        for (uint32_t k = 0; k < it->corners; k++) {
            double p[3] = {it->x[k], it->y[k], it->z[k]};
            for (int a = 0; a < 3; a++) {
                ch->lo[a] = fmin(ch->lo[a], p[a]);
                ch->hi[a] = fmax(ch->hi[a], p[a]);
            }
        }
        n++;
    }
    if (ch)
        chunk_close(hc, ch);
    hc->num_items = n;
}

il_status il_hemicube_create(const il_patch_mesh *mesh, uint32_t resolution, il_hemicube **out,
                             il_error *err)
{
    *out = NULL;
    if (resolution < 2 || resolution > 8192)
        return il_fail(err, IL_ERR_INVALID,
                       "hemicube resolution %u is out of range (2 to 8192)", resolution);
    resolution += resolution & 1u; /* the side faces need an even resolution */
    il_hemicube *hc = il_calloc(1, sizeof *hc, err);
    if (!hc)
        return IL_ERR_MEMORY;
    hc->mesh = mesh;
    hc->res = resolution;
    uint32_t h = hc->half = resolution / 2;
    size_t num_items = mesh->num_patches;
    for (uint32_t t = 0; t < mesh->num_tris; t++)
        num_items += mesh->tri_patch[t] == IL_NO_PATCH && !is_pane(mesh, t);
    size_t cap = num_items ? num_items : 1;
    /* At most one chunk per item; usually ~num_items / 64. */
    hc->top = il_malloc((size_t)h * (h + 1) / 2 * sizeof(float), err);
    hc->side = il_malloc((size_t)h * h * sizeof(float), err);
    hc->top_cum = il_malloc((size_t)h * (h + 1) * sizeof(double), err);
    hc->side_cum = il_malloc((size_t)h * (h + 1) * sizeof(double), err);
    hc->fold = il_malloc(resolution * sizeof(uint32_t), err);
    hc->items = il_malloc(cap * sizeof *hc->items, err);
    hc->item_id = il_malloc(cap * sizeof *hc->item_id, err);
    hc->chunks = il_malloc(cap * sizeof *hc->chunks, err);
    if (!hc->top || !hc->side || !hc->top_cum || !hc->side_cum || !hc->fold || !hc->items ||
        !hc->item_id || !hc->chunks) {
        il_hemicube_release(hc);
        return IL_ERR_MEMORY;
    }
    build_items(hc);
    /* Shrink the chunk array to what was used (never fails to keep the old). */
    il_hc_chunk *shrunk = realloc(hc->chunks, (hc->num_chunks ? hc->num_chunks : 1) * sizeof *shrunk);
    if (shrunk)
        hc->chunks = shrunk;
    for (uint32_t p = 0; p < resolution; p++)
        hc->fold[p] = p < h ? h - 1 - p : p - h;
    /* Exact per-pixel form factors from the hemicube centre (normal +z). */
    float px = 2.0f / (float)resolution;
    il_vec3 o = v3(0.0f, 0.0f, 0.0f), up = v3(0.0f, 0.0f, 1.0f);
    for (uint32_t a = 0; a < h; a++) {
        for (uint32_t b = 0; b <= a; b++) {
            float x0 = (float)a * px, x1 = (float)(a + 1) * px;
            float y0 = (float)b * px, y1 = (float)(b + 1) * px;
            il_vec3 sq[4] = {v3(x0, y0, 1.0f), v3(x1, y0, 1.0f), v3(x1, y1, 1.0f), v3(x0, y1, 1.0f)};
            hc->top[a * (a + 1) / 2 + b] = (float)il_ff_point_polygon(o, up, sq, 4);
        }
    }
    for (uint32_t r = 0; r < h; r++) {
        for (uint32_t c = 0; c < h; c++) {
            float y0 = (float)c * px, y1 = (float)(c + 1) * px;
            float z0 = (float)r * px, z1 = (float)(r + 1) * px;
            il_vec3 sq[4] = {v3(1.0f, y0, z0), v3(1.0f, y1, z0), v3(1.0f, y1, z1), v3(1.0f, y0, z1)};
            hc->side[r * h + c] = (float)il_ff_point_polygon(o, up, sq, 4);
        }
    }
    /* Running sums along each distinct row (of the stored float values). */
    for (uint32_t r = 0; r < h; r++) {
        double *tc = hc->top_cum + (size_t)r * (h + 1), *sc = hc->side_cum + (size_t)r * (h + 1);
        tc[0] = sc[0] = 0.0;
        for (uint32_t m = 0; m < h; m++) {
            uint32_t hi = m > r ? m : r, lo = m > r ? r : m;
            tc[m + 1] = tc[m] + (double)hc->top[hi * (hi + 1) / 2 + lo];
            sc[m + 1] = sc[m] + (double)hc->side[(size_t)r * h + m];
        }
    }
    *out = hc;
    return IL_OK;
}

void il_hemicube_release(il_hemicube *hc)
{
    if (!hc)
        return;
    free(hc->top);
    free(hc->side);
    free(hc->top_cum);
    free(hc->side_cum);
    free(hc->fold);
    free(hc->items);
    free(hc->item_id);
    free(hc->chunks);
    free(hc);
}

il_status il_hemicube_buffers_create(const il_hemicube *hc, il_hemicube_buffers **out,
                                     il_error *err)
{
    *out = NULL;
    il_hemicube_buffers *b = il_calloc(1, sizeof *b, err);
    if (!b)
        return IL_ERR_MEMORY;
    b->hc = hc;
    size_t rows = (size_t)hc->res * 3, pixels = rows * hc->res;
    /* 4 pixels of padding at both ends for the four-wide loops. */
    b->ids_mem = il_malloc((pixels + 8) * sizeof *b->ids, err);
    b->depth_mem = b->ids_mem ? il_calloc(pixels + 8, sizeof *b->depth, err) : NULL;
    /* malloc aligns to 16 bytes on every x86-64 ABI; the four-wide loops rely on it. */
    b->ids = b->ids_mem ? b->ids_mem + 4 : NULL;
    b->depth = b->depth_mem ? b->depth_mem + 4 : NULL;
    b->span = b->depth ? il_malloc(rows * sizeof *b->span * 2, err) : NULL;
    b->scratch = b->span ? il_calloc(hc->mesh->num_patches ? hc->mesh->num_patches : 1,
                                     sizeof *b->scratch, err)
                         : NULL;
    if (!b->scratch) {
        il_hemicube_buffers_release(b);
        return IL_ERR_MEMORY;
    }
    /* Kept clean between rows: empty ids, zero depth, empty spans. */
    memset(b->ids_mem, 0xff, (pixels + 8) * sizeof *b->ids);
    for (size_t r = 0; r < rows; r++) {
        b->span[2 * r] = (int32_t)hc->res;
        b->span[2 * r + 1] = 0;
    }
    *out = b;
    return IL_OK;
}

void il_hemicube_buffers_release(il_hemicube_buffers *b)
{
    if (!b)
        return;
    free(b->ids_mem);
    free(b->depth_mem);
    free(b->span);
    free(b->scratch);
    free(b);
}

/* Face coordinates (a, b, d) of a local point (x, y, z): screen axes a, b
 * and depth d along the face's outward axis.  Face 0 is the top; 1-4 the
 * sides x=+1, x=-1, y=+1, y=-1, whose b is the height z. */
static inline fvert to_face(int f, float x, float y, float z)
{
    switch (f) {
    case 0: return (fvert){x, y, z};
    case 1: return (fvert){y, z, x};
    case 2: return (fvert){-y, z, -x};
    case 3: return (fvert){-x, z, y};
    default: return (fvert){x, z, -y};
    }
}

/* Signed distance to clip plane `p` of a face (>= 0 inside). */
static inline float plane_dist(int p, bool top, float near, fvert v)
{
    switch (p) {
    case 0: return v.d - v.a;
    case 1: return v.d + v.a;
    case 2: return v.d - v.b;
    case 3: return top ? v.d + v.b : v.b;
    default: return v.d - near;
    }
}

static inline unsigned outcode(bool top, float near, fvert v)
{
    unsigned c = 0;
    c |= (v.d - v.a < 0.0f) << 0;
    c |= (v.d + v.a < 0.0f) << 1;
    c |= (v.d - v.b < 0.0f) << 2;
    c |= ((top ? v.d + v.b : v.b) < 0.0f) << 3;
    c |= (v.d - near < 0.0f) << 4;
    return c;
}

/* Sutherland-Hodgman against one plane; returns the new vertex count. */
static int clip_plane(int p, bool top, float near, const fvert *in, int n, fvert *out)
{
    int m = 0;
    fvert a = in[n - 1];
    float da = plane_dist(p, top, near, a);
    for (int k = 0; k < n; k++) {
        fvert b = in[k];
        float db = plane_dist(p, top, near, b);
        if ((da >= 0.0f) != (db >= 0.0f) && m < IL_HC_MAX_VERTS) {
            float t = da / (da - db);
            out[m++] = (fvert){a.a + (b.a - a.a) * t, a.b + (b.b - a.b) * t, a.d + (b.d - a.d) * t};
        }
        if (db >= 0.0f && m < IL_HC_MAX_VERTS)
            out[m++] = b;
        a = b;
        da = db;
    }
    return m;
}

#if !IL_HC_SIMD
/* Local (x, y, z) -> face (a, b, d) for faces 0-4 (the rows of to_face). */
static const float il_hc_face_m[5][9] = {
    {1, 0, 0, 0, 1, 0, 0, 0, 1},  {0, 1, 0, 0, 0, 1, 1, 0, 0}, {0, -1, 0, 0, 0, 1, -1, 0, 0},
    {-1, 0, 0, 0, 0, 1, 0, 1, 0}, {1, 0, 0, 0, 0, 1, 0, -1, 0},
};

/* The faces whose closed frustum (near plane included) holds a local point:
 * bit f for face f, the planes of outcode() written out for all five. */
static inline unsigned face_mask(float x, float y, float z, float near)
{
    unsigned up = z >= 0.0f;
    unsigned t = (z >= x) & (z >= -x) & (z >= y) & (z >= -y) & (z >= near);
    unsigned px = (x >= y) & (x >= -y) & (x >= z) & up & (x >= near);
    unsigned nx = (-x >= y) & (-x >= -y) & (-x >= z) & up & (-x >= near);
    unsigned py = (y >= x) & (y >= -x) & (y >= z) & up & (y >= near);
    unsigned ny = (-y >= x) & (-y >= -x) & (-y >= z) & up & (-y >= near);
    return t | px << 1 | nx << 2 | py << 3 | ny << 4;
}
#endif

/* ceilf for |v| < 2^31 without a libm call (no SSE4.1 round): truncation
 * rounds towards zero, which is the ceiling for negatives. */
static inline int ceil_int(float v)
{
    int t = (int)v;
    return t + (v > (float)t);
}

/* Writes pixels [x0, x1) of a row where 1/depth w = wa (x + 0.5) + w0 is
 * nearer than what is there; x counts from the row's start at `row`, an
 * index into the buffers. */
static inline void span_write(float *depth, uint32_t *ids, size_t row, int x0, int x1, float wa,
                              float w0, uint32_t id)
{
#if IL_HC_SIMD
    /* Four pixels at a time on 16-byte aligned groups of the buffers (so a
     * load after an overlapping store forwards instead of stalling); lanes
     * outside [x0, x1) are masked off and rewrite their own value (the
     * buffers are padded and aligned at both ends). */
    size_t a0 = (row + (size_t)x0) & ~(size_t)3, a1 = row + (size_t)x1;
    int first = (int)(a0 - row); /* x of the first lane, x0 - 3 .. x0 */
    const __m128 lane = _mm_set_ps(3.5f, 2.5f, 1.5f, 0.5f);
    const __m128i lane_i = _mm_set_epi32(3, 2, 1, 0);
    __m128 vwa = _mm_set1_ps(wa), vw0 = _mm_set1_ps(w0);
    __m128i vid = _mm_set1_epi32((int)id);
    __m128i lo = _mm_set1_epi32(x0 - 1), hi = _mm_set1_epi32(x1);
    for (size_t a = a0; a < a1; a += 4, first += 4) {
        __m128i xi = _mm_add_epi32(_mm_set1_epi32(first), lane_i);
        __m128 w = _mm_add_ps(_mm_mul_ps(vwa, _mm_add_ps(_mm_set1_ps((float)first), lane)), vw0);
        __m128 d = _mm_load_ps(depth + a);
        __m128i old = _mm_load_si128((const __m128i *)(ids + a));
        __m128i in = _mm_and_si128(_mm_cmpgt_epi32(xi, lo), _mm_cmplt_epi32(xi, hi));
        __m128i m = _mm_and_si128(_mm_castps_si128(_mm_cmpgt_ps(w, d)), in);
        __m128 mf = _mm_castsi128_ps(m);
        _mm_store_ps(depth + a, _mm_or_ps(_mm_and_ps(mf, w), _mm_andnot_ps(mf, d)));
        _mm_store_si128((__m128i *)(ids + a), _mm_or_si128(_mm_and_si128(m, vid), _mm_andnot_si128(m, old)));
    }
#else
    for (int px = x0; px < x1; px++) {
        float w = wa * ((float)px + 0.5f) + w0;
        if (w > depth[row + px]) {
            depth[row + px] = w;
            ids[row + px] = id;
        }
    }
#endif
}

/* Scan-converts a convex polygon on face f given in face coordinates
 * (inside the face's frustum), keeping the nearest id per pixel centre.
 * 1/depth = NF.(u, v, 1) / k with u, v the face's coordinates in [-1,1]. */
static void raster(const il_hemicube *hc, il_hemicube_buffers *buf, int f, const fvert *poly,
                   int n, fvert nf, float ik, uint32_t id)
{
    bool top = f == 0;
    int res = (int)hc->res, h = (int)hc->half;
    int height = top ? res : h;
    float fh = (float)h, voff = top ? 1.0f : 0.0f;
    float sx[IL_HC_MAX_VERTS], sy[IL_HC_MAX_VERTS];
    float ymin = INFINITY, ymax = -INFINITY;
    for (int v = 0; v < n; v++) {
        float inv = fh / poly[v].d;
        sx[v] = poly[v].a * inv + fh;
        sy[v] = poly[v].b * inv + voff * fh;
        ymin = il_minf(ymin, sy[v]);
        ymax = il_maxf(ymax, sy[v]);
    }
    int y0 = ceil_int(ymin - 0.5f), y1 = ceil_int(ymax - 0.5f);
    if (y0 < 0)
        y0 = 0;
    if (y1 > height)
        y1 = height;
    if (y0 >= y1)
        return;
    /* Orientation, then each edge as a line x = ex + (y - ey) es taken from
     * its lower end, bounding the rows from the left (el) or the right.  A
     * horizontal edge becomes a line that bounds nothing: the rows' range
     * already does. */
    float area = 0.0f;
    for (int k = 0, l = n - 1; k < n; l = k++)
        area += sx[l] * sy[k] - sx[k] * sy[l];
    if (area == 0.0f)
        return;
    float ex[IL_HC_MAX_VERTS], ey[IL_HC_MAX_VERTS], es[IL_HC_MAX_VERTS];
    bool el[IL_HC_MAX_VERTS];
    for (int k = 0, l = n - 1; k < n; l = k++) {
        float dy = sy[k] - sy[l];
        bool down = dy > 0.0f;
        int lo = down ? l : k, hi = down ? k : l;
        bool flat = !(fabsf(dy) > 1e-6f);
        el[k] = flat || down != (area > 0.0f);
        ex[k] = flat ? -1e30f : sx[lo];
        ey[k] = flat ? 0.0f : sy[lo];
        es[k] = flat ? 0.0f : (sx[hi] - sx[lo]) / (sy[hi] - sy[lo]);
    }
    float fw = (float)res;
    /* 1/d = NF.(u, v, 1) / k with u = sx/h - 1, v = sy/h - voff. */
    float wa = nf.a * ik / fh, wb = nf.b * ik / fh;
    float wc = (nf.d - nf.a - nf.b * voff) * ik;
    size_t row0 = top ? 0 : (size_t)res + (size_t)(f - 1) * (size_t)h;
    int32_t *span = buf->span + 2 * row0;
    for (int py = y0; py < y1; py++) {
        float yc = (float)py + 0.5f;
        float xl = 0.0f, xr = fw;
        for (int e = 0; e < n; e++) {
            float x = ex[e] + (yc - ey[e]) * es[e];
            xl = el[e] ? il_maxf(xl, x) : xl;
            xr = el[e] ? xr : il_minf(xr, x);
        }
        /* (Both stay in [0, res]: safe to convert.) */
        int x0 = ceil_int(il_minf(xl, fw) - 0.5f), x1 = ceil_int(il_maxf(xr, 0.0f) - 0.5f);
        if (x0 >= x1)
            continue;
        int32_t *sp = span + 2 * py;
        sp[0] = x0 < sp[0] ? x0 : sp[0];
        sp[1] = x1 > sp[1] ? x1 : sp[1];
        span_write(buf->depth, buf->ids, (row0 + (size_t)py) * (size_t)res, x0, x1, wa,
                   wb * yc + wc, id);
    }
}

static void draw_clipped(const il_hemicube *hc, il_hemicube_buffers *buf, const il_vec3 *loc,
                         int n, il_vec3 nrm, float ik, float near, uint32_t id);

#if !IL_HC_SIMD
/* Projects one planar convex polygon (local coordinates, unit plane normal
 * nrm, plane nrm.x = k) onto the five faces. */
static void draw_polygon(const il_hemicube *hc, il_hemicube_buffers *buf, const il_vec3 *loc,
                         int n, il_vec3 nrm, float k, float near, uint32_t id)
{
    float ik = 1.0f / k;
    /* The common case: all corners inside one face's frustum. */
    unsigned inside = 0x1f;
    for (int v = 0; v < n; v++)
        inside &= face_mask(loc[v].x, loc[v].y, loc[v].z, near);
    if (inside) {
        int f = 0;
        while (!(inside & (1u << f)))
            f++;
        const float *m = il_hc_face_m[f];
        fvert va[4];
        for (int v = 0; v < n; v++)
            va[v] = (fvert){m[0] * loc[v].x + m[1] * loc[v].y + m[2] * loc[v].z,
                            m[3] * loc[v].x + m[4] * loc[v].y + m[5] * loc[v].z,
                            m[6] * loc[v].x + m[7] * loc[v].y + m[8] * loc[v].z};
        raster(hc, buf, f, va, n, to_face(f, nrm.x, nrm.y, nrm.z), ik, id);
        return;
    }
    draw_clipped(hc, buf, loc, n, nrm, ik, near, id);
}
#endif

#if IL_HC_SIMD
/* Four-lane helpers: horizontal min, max and sum (fixed order), and the
 * lanes rotated by one (v1, v2, v3, v0): each lane's next corner. */
static inline float hmin4(__m128 v)
{
    v = _mm_min_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_cvtss_f32(_mm_min_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2))));
}
static inline float hmax4(__m128 v)
{
    v = _mm_max_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_cvtss_f32(_mm_max_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2))));
}
static inline float hsum4(__m128 v)
{
    v = _mm_add_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(2, 3, 0, 1)));
    return _mm_cvtss_f32(_mm_add_ps(v, _mm_shuffle_ps(v, v, _MM_SHUFFLE(1, 0, 3, 2))));
}
static inline __m128 next4(__m128 v) { return _mm_shuffle_ps(v, v, _MM_SHUFFLE(0, 3, 2, 1)); }
static inline __m128 select4(__m128 m, __m128 a, __m128 b)
{
    return _mm_or_ps(_mm_and_ps(m, a), _mm_andnot_ps(m, b));
}

/* raster() for a polygon of four corners (a triangle repeats its first)
 * held one per lane: the same projection, edge lines and spans. */
static void raster4(const il_hemicube *hc, il_hemicube_buffers *buf, int f, __m128 A, __m128 B,
                    __m128 D, fvert nf, float ik, uint32_t id)
{
    bool top = f == 0;
    int res = (int)hc->res, h = (int)hc->half;
    int height = top ? res : h;
    float fh = (float)h, voff = top ? 1.0f : 0.0f;
    __m128 vfh = _mm_set1_ps(fh);
    __m128 inv = _mm_div_ps(vfh, D);
    __m128 sx = _mm_add_ps(_mm_mul_ps(A, inv), vfh);
    __m128 sy = _mm_add_ps(_mm_mul_ps(B, inv), _mm_set1_ps(voff * fh));
    int y0 = ceil_int(hmin4(sy) - 0.5f), y1 = ceil_int(hmax4(sy) - 0.5f);
    if (y0 < 0)
        y0 = 0;
    if (y1 > height)
        y1 = height;
    if (y0 >= y1)
        return;
    __m128 sxn = next4(sx), syn = next4(sy);
    float area = hsum4(_mm_sub_ps(_mm_mul_ps(sx, syn), _mm_mul_ps(sxn, sy)));
    if (area == 0.0f)
        return;
    __m128 dy = _mm_sub_ps(syn, sy);
    __m128 down = _mm_cmpgt_ps(dy, _mm_setzero_ps());
    __m128 flat = _mm_cmpngt_ps(_mm_andnot_ps(_mm_set1_ps(-0.0f), dy), _mm_set1_ps(1e-6f));
    __m128 ccw = area > 0.0f ? _mm_castsi128_ps(_mm_set1_epi32(-1)) : _mm_setzero_ps();
    __m128 left = _mm_or_ps(flat, _mm_xor_ps(down, ccw));
    __m128 ex = select4(flat, _mm_set1_ps(-1e30f), select4(down, sx, sxn));
    __m128 ey = _mm_andnot_ps(flat, select4(down, sy, syn));
    __m128 es = _mm_andnot_ps(flat, _mm_div_ps(_mm_sub_ps(sxn, sx), dy));
    const __m128 neg_inf = _mm_set1_ps(-INFINITY), pos_inf = _mm_set1_ps(INFINITY);
    float wa = nf.a * ik / fh, wb = nf.b * ik / fh;
    float wc = (nf.d - nf.a - nf.b * voff) * ik;
    size_t row0 = top ? 0 : (size_t)res + (size_t)(f - 1) * (size_t)h;
    int32_t *span = buf->span + 2 * row0;
    /* Each edge's line broadcast to all lanes; its side as an all-lanes
     * mask with -inf/+inf standing in on the side it does not bound. */
#define IL_HC_EDGE(e)                                                                         \
    __m128 ex##e = _mm_shuffle_ps(ex, ex, _MM_SHUFFLE(e, e, e, e));                           \
    __m128 ey##e = _mm_shuffle_ps(ey, ey, _MM_SHUFFLE(e, e, e, e));                           \
    __m128 es##e = _mm_shuffle_ps(es, es, _MM_SHUFFLE(e, e, e, e));                           \
    __m128 el##e = _mm_shuffle_ps(left, left, _MM_SHUFFLE(e, e, e, e))
    IL_HC_EDGE(0);
    IL_HC_EDGE(1);
    IL_HC_EDGE(2);
    IL_HC_EDGE(3);
#undef IL_HC_EDGE
    const __m128 row_step = _mm_set_ps(3.5f, 2.5f, 1.5f, 0.5f), half = _mm_set1_ps(0.5f);
    /* Four rows at a time: the span ends of each row (lanes are rows). */
    for (int py = y0; py < y1; py += 4) {
        __m128 yc = _mm_add_ps(_mm_set1_ps((float)py), row_step);
        __m128 xl = _mm_setzero_ps(), xr = _mm_set1_ps((float)res);
#define IL_HC_BOUND(e)                                                                        \
    do {                                                                                      \
        __m128 x = _mm_add_ps(ex##e, _mm_mul_ps(_mm_sub_ps(yc, ey##e), es##e));               \
        xl = _mm_max_ps(xl, select4(el##e, x, neg_inf));                                      \
        xr = _mm_min_ps(xr, select4(el##e, pos_inf, x));                                      \
    } while (0)
        IL_HC_BOUND(0);
        IL_HC_BOUND(1);
        IL_HC_BOUND(2);
        IL_HC_BOUND(3);
#undef IL_HC_BOUND
        /* ceil(x - 0.5) per lane, as ceil_int does. */
        xl = _mm_min_ps(xl, _mm_set1_ps((float)res));
        xr = _mm_max_ps(xr, _mm_setzero_ps());
        __m128 vl = _mm_sub_ps(xl, half), vr = _mm_sub_ps(xr, half);
        __m128i tl = _mm_cvttps_epi32(vl), tr = _mm_cvttps_epi32(vr);
        tl = _mm_sub_epi32(tl, _mm_castps_si128(_mm_cmpgt_ps(vl, _mm_cvtepi32_ps(tl))));
        tr = _mm_sub_epi32(tr, _mm_castps_si128(_mm_cmpgt_ps(vr, _mm_cvtepi32_ps(tr))));
        int32_t x0s[4], x1s[4];
        _mm_storeu_si128((__m128i *)x0s, tl);
        _mm_storeu_si128((__m128i *)x1s, tr);
        int rows = y1 - py < 4 ? y1 - py : 4;
        for (int r = 0; r < rows; r++) {
            int x0 = x0s[r], x1 = x1s[r];
            if (x0 >= x1)
                continue;
            int32_t *sp = span + 2 * (py + r);
            sp[0] = x0 < sp[0] ? x0 : sp[0];
            sp[1] = x1 > sp[1] ? x1 : sp[1];
            float ycr = (float)(py + r) + 0.5f;
            span_write(buf->depth, buf->ids, (row0 + (size_t)(py + r)) * (size_t)res, x0, x1, wa,
                       wb * ycr + wc, id);
        }
    }
}

/* One item in four lanes: local coordinates, the faces holding all its
 * corners, and raster4 when one does; otherwise the clipping path. */
static void draw_item4(const il_hemicube *hc, il_hemicube_buffers *buf, const il_hc_item *it,
                       il_vec3 c, const il_frame *fr, il_vec3 nrm, float k, float near, uint32_t id)
{
    __m128 X = _mm_sub_ps(_mm_loadu_ps(it->x), _mm_set1_ps(c.x));
    __m128 Y = _mm_sub_ps(_mm_loadu_ps(it->y), _mm_set1_ps(c.y));
    __m128 Z = _mm_sub_ps(_mm_loadu_ps(it->z), _mm_set1_ps(c.z));
#define IL_HC_DOT(e) _mm_add_ps(_mm_add_ps(_mm_mul_ps(X, _mm_set1_ps(e.x)), _mm_mul_ps(Y, _mm_set1_ps(e.y))), \
                                _mm_mul_ps(Z, _mm_set1_ps(e.z)))
    __m128 lx = IL_HC_DOT(fr->s), ly = IL_HC_DOT(fr->t), lz = IL_HC_DOT(fr->n);
#undef IL_HC_DOT
    __m128 zero = _mm_setzero_ps();
    if (!_mm_movemask_ps(_mm_cmpgt_ps(lz, zero)))
        return; /* all corners on or below the base plane */
    __m128 nx = _mm_sub_ps(zero, lx), ny = _mm_sub_ps(zero, ly), vn = _mm_set1_ps(near);
    __m128 up = _mm_cmpge_ps(lz, zero);
#define IL_HC_IN(d, p, q, r, s) _mm_movemask_ps(_mm_and_ps(_mm_and_ps(_mm_and_ps(_mm_cmpge_ps(d, p), \
    _mm_cmpge_ps(d, q)), _mm_and_ps(_mm_cmpge_ps(d, r), s)), _mm_cmpge_ps(d, vn))) == 0xf
    unsigned inside = (unsigned)(IL_HC_IN(lz, lx, nx, ly, _mm_cmpge_ps(lz, ny))) |
                      (unsigned)(IL_HC_IN(lx, ly, ny, lz, up)) << 1 |
                      (unsigned)(IL_HC_IN(nx, ly, ny, lz, up)) << 2 |
                      (unsigned)(IL_HC_IN(ly, lx, nx, lz, up)) << 3 |
                      (unsigned)(IL_HC_IN(ny, lx, nx, lz, up)) << 4;
#undef IL_HC_IN
    float ik = 1.0f / k;
    if (inside) {
        int f = __builtin_ctz(inside);
        __m128 A, B, D;
        switch (f) {
        case 0: A = lx, B = ly, D = lz; break;
        case 1: A = ly, B = lz, D = lx; break;
        case 2: A = ny, B = lz, D = nx; break;
        case 3: A = nx, B = lz, D = ly; break;
        default: A = lx, B = lz, D = ny; break;
        }
        raster4(hc, buf, f, A, B, D, to_face(f, nrm.x, nrm.y, nrm.z), ik, id);
        return;
    }
    float fx[4], fy[4], fz[4];
    _mm_storeu_ps(fx, lx);
    _mm_storeu_ps(fy, ly);
    _mm_storeu_ps(fz, lz);
    il_vec3 loc[4];
    int n = (int)it->corners;
    for (int v = 0; v < n; v++)
        loc[v] = v3(fx[v], fy[v], fz[v]);
    draw_clipped(hc, buf, loc, n, nrm, ik, near, id);
}
#endif

/* The general path: per face, outcodes and Sutherland-Hodgman clipping
 * against the planes some corner violates. */
static void draw_clipped(const il_hemicube *hc, il_hemicube_buffers *buf, const il_vec3 *loc,
                         int n, il_vec3 nrm, float ik, float near, uint32_t id)
{
    for (int f = 0; f < 5; f++) {
        bool top = f == 0;
        fvert va[IL_HC_MAX_VERTS], vb[IL_HC_MAX_VERTS];
        unsigned all = 0x1f, any = 0;
        for (int v = 0; v < n; v++) {
            va[v] = to_face(f, loc[v].x, loc[v].y, loc[v].z);
            unsigned c = outcode(top, near, va[v]);
            all &= c;
            any |= c;
        }
        if (all)
            continue;
        fvert *poly = va;
        int m = n;
        for (int p = 0; p < 5 && m >= 3; p++) {
            if (!(any & (1u << p)))
                continue;
            fvert *dst = poly == va ? vb : va;
            m = clip_plane(p, top, near, poly, m, dst);
            poly = dst;
        }
        if (m < 3)
            continue;
#if IL_HC_SIMD
        if (m <= 4) { /* a triangle repeats its first corner */
            float a[4], b[4], d[4];
            for (int v = 0; v < 4; v++) {
                const fvert *q = &poly[v < m ? v : 0];
                a[v] = q->a, b[v] = q->b, d[v] = q->d;
            }
            raster4(hc, buf, f, _mm_loadu_ps(a), _mm_loadu_ps(b), _mm_loadu_ps(d),
                    to_face(f, nrm.x, nrm.y, nrm.z), ik, id);
            continue;
        }
#endif
        raster(hc, buf, f, poly, m, to_face(f, nrm.x, nrm.y, nrm.z), ik, id);
    }
}

/* Whether a chunk can be skipped whole from the centre c (normal nn): its
 * box lies on or behind the base plane, or it is planar and its plane
 * passes within `near` of c (every item edge-on). */
static bool chunk_hidden(const il_hc_chunk *ch, il_vec3 c, il_vec3 nn, float near)
{
    double cc[3] = {c.x, c.y, c.z}, nv[3] = {nn.x, nn.y, nn.z}, top = 0.0;
    for (int a = 0; a < 3; a++)
        top += nv[a] * ((nv[a] > 0.0 ? ch->hi[a] : ch->lo[a]) - cc[a]);
    if (top <= 0.0)
        return true;
    if (ch->planar) {
        double dist = ch->n[0] * cc[0] + ch->n[1] * cc[1] + ch->n[2] * cc[2] - ch->d;
        if (fabs(dist) + ch->tol <= (double)near)
            return true;
    }
    return false;
}

/* Adds the delta form factors of pixels [x0, x1) of one row (running sums
 * cum of its folded columns) to patch id's tally. */
static inline void add_run(const double *cum, uint32_t h, uint32_t id, uint32_t x0, uint32_t x1,
                           float *acc, il_ff_row *out)
{
    /* G(x) = (sum over pixels [0, x)) - (sum over [0, h)): the columns fold
     * about h, so it is cum[x - h] right of the centre and -cum[h - x] left. */
    double g1 = x1 >= h ? cum[x1 - h] : -cum[h - x1];
    double g0 = x0 >= h ? cum[x0 - h] : -cum[h - x0];
    /* List the patch the first time (the slot past the end is free: a row
     * never holds all num_patches entries, as it lacks patch i). */
    out->index[out->count] = id;
    out->count += acc[id] == 0.0f;
    acc[id] += (float)(g1 - g0);
}

/* Sums the delta form factors per id over the written pixels, a run of one
 * id at a time, and clears what was written. */
static void gather(const il_hemicube *hc, il_hemicube_buffers *buf, il_ff_row *out)
{
    uint32_t res = hc->res, h = hc->half;
    float *acc = buf->scratch;
    for (uint32_t r = 0; r < 3 * res; r++) {
        int32_t x0 = buf->span[2 * r], x1 = buf->span[2 * r + 1];
        if (x0 >= x1)
            continue;
        const double *cum = r < res ? hc->top_cum + (size_t)hc->fold[r] * (h + 1)
                                    : hc->side_cum + (size_t)((r - res) % h) * (h + 1);
        uint32_t *row = buf->ids + (size_t)r * res;
        uint32_t run_id = row[x0];
        uint32_t start = (uint32_t)x0;
        /* Run boundaries (pixels whose id differs from the one before),
         * found 64 pixels at a time as a bit mask. */
        for (int32_t bx = x0 + 1; bx < x1; bx += 64) {
            int32_t be = bx + 64 < x1 ? bx + 64 : x1;
            uint64_t mask = 0;
#if IL_HC_SIMD
            for (int32_t px = bx; px < be; px += 4) {
                __m128i a = _mm_loadu_si128((const __m128i *)(row + px));
                __m128i p = _mm_loadu_si128((const __m128i *)(row + px - 1));
                unsigned eq = (unsigned)_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(a, p)));
                mask |= (uint64_t)(~eq & 0xfu) << (px - bx);
            }
            if (be - bx < 64)
                mask &= ((uint64_t)1 << (be - bx)) - 1;
#else
            for (int32_t px = bx; px < be; px++)
                mask |= (uint64_t)(row[px] != row[px - 1]) << (px - bx);
#endif
            while (mask) {
                uint32_t px = (uint32_t)bx + (uint32_t)__builtin_ctzll(mask);
                mask &= mask - 1;
                if (run_id != IL_HC_NONE)
                    add_run(cum, h, run_id, start, px, acc, out);
                run_id = row[px];
                start = px;
            }
        }
        if (run_id != IL_HC_NONE)
            add_run(cum, h, run_id, start, (uint32_t)x1, acc, out);
        memset(row + x0, 0xff, (size_t)(x1 - x0) * sizeof *row);
        memset(buf->depth + (size_t)r * res + x0, 0, (size_t)(x1 - x0) * sizeof(float));
        buf->span[2 * r] = (int32_t)res;
        buf->span[2 * r + 1] = 0;
    }
}

void il_hemicube_row(const il_hemicube *hc, il_hemicube_buffers *buf, uint32_t i, il_ff_row *out)
{
    const il_patch_mesh *mesh = hc->mesh;
    out->count = 0;
    if (i >= mesh->num_patches)
        return;
    const il_patch *pi = &mesh->patches[i];
    il_frame fr = il_frame_from_normal(pi->normal);
    il_vec3 c = pi->center;
    /* The near plane: far below the patch's size, far above float noise. */
    float near = 1e-4f * sqrtf(il_maxf(pi->area, 0.0f));
    if (!(near > 0.0f))
        near = 1e-8f;

    for (uint32_t ci = 0; ci < hc->num_chunks; ci++) {
        const il_hc_chunk *ch = &hc->chunks[ci];
        if (chunk_hidden(ch, c, fr.n, near))
            continue;
        for (uint32_t j = ch->first; j < ch->first + ch->count; j++) {
            const il_hc_item *it = &hc->items[j];
            uint32_t id = hc->item_id[j];
            if (id == i)
                continue;
            il_vec3 nw = v3(it->n[0], it->n[1], it->n[2]);
            il_vec3 d0 = v3(it->x[0] - c.x, it->y[0] - c.y, it->z[0] - c.z);
            /* Plane nw.x = k in local coordinates: the front faces the
             * centre when k < 0. */
            float k = v3_dot(nw, d0);
            if (!(fabsf(k) > near))
                continue; /* its plane passes through the centre: covers no pixel */
            /* A back face (or an occluder) receives nothing but hides what
             * lies behind it. */
            uint32_t draw_id = k < 0.0f ? id : IL_HC_NONE;
            il_vec3 nrm = il_frame_to_local(&fr, nw);
#if IL_HC_SIMD
            draw_item4(hc, buf, it, c, &fr, nrm, k, near, draw_id);
#else
            int n = (int)it->corners;
            il_vec3 loc[4];
            bool above = false;
            for (int v = 0; v < n; v++) {
                il_vec3 d = v3(it->x[v] - c.x, it->y[v] - c.y, it->z[v] - c.z);
                loc[v] = il_frame_to_local(&fr, d);
                above |= loc[v].z > 0.0f;
            }
            if (above)
                draw_polygon(hc, buf, loc, n, nrm, k, near, draw_id);
#endif
        }
    }
    gather(hc, buf, out);
    il_ff_row_compact(buf->scratch, mesh->num_patches, 1.0f, out);
}
