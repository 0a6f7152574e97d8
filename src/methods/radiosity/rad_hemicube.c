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
 * four.  At res 256: 8,256 + 16,384 floats (97 KiB).
 *
 * Per primitive: local coordinates, reject when wholly below the base plane,
 * back-face cull (patches only), then per face an outcode test against the
 * face's frustum (4 side planes + a near plane): all vertices outside one
 * plane rejects; only planes some vertex violates are clipped
 * (Sutherland-Hodgman).  Scan conversion samples pixel centres on
 * half-open spans (no pixel is shared by two abutting polygons) and
 * interpolates 1/depth, which is affine in screen space for a plane. */
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/radiosity/rad_ff_internal.h"

#define IL_HC_MAX_VERTS 16
#define IL_HC_NONE UINT32_MAX

struct il_hemicube {
    const il_rad_mesh *mesh;
    uint32_t res, half;
    float *top;              /* octant: index hi*(hi+1)/2 + lo of the folded pixel */
    float *side;             /* quadrant: [row in z][folded column] */
    uint32_t *fold;          /* res: pixel column/row -> distance from the centre line */
    float *patch_xyz;        /* 4 corners x 3 floats per patch (packed for the cache) */
    uint32_t *occluders;     /* triangles with no patch */
    uint32_t num_occluders;
};

struct il_hemicube_buffers {
    const il_hemicube *hc;
    uint32_t *ids;           /* top res*res, then four sides res*half each */
    float *depth;            /* 1/depth, 0 = empty */
    float *scratch;          /* num_patches tallies, kept zeroed */
};

typedef struct { float a, b, d; } fvert;

il_status il_hemicube_create(const il_rad_mesh *mesh, uint32_t resolution, il_hemicube **out,
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
    hc->top = il_malloc((size_t)h * (h + 1) / 2 * sizeof(float), err);
    hc->side = il_malloc((size_t)h * h * sizeof(float), err);
    hc->fold = il_malloc(resolution * sizeof(uint32_t), err);
    hc->patch_xyz = il_malloc((size_t)(mesh->num_patches ? mesh->num_patches : 1) * 12 * sizeof(float), err);
    uint32_t num_occ = 0;
    for (uint32_t t = 0; t < mesh->num_tris; t++)
        num_occ += mesh->tri_patch[t] == IL_RAD_NO_PATCH;
    hc->occluders = il_malloc((num_occ ? num_occ : 1) * sizeof(uint32_t), err);
    if (!hc->top || !hc->side || !hc->fold || !hc->patch_xyz || !hc->occluders) {
        il_hemicube_release(hc);
        return IL_ERR_MEMORY;
    }
    for (uint32_t t = 0; t < mesh->num_tris; t++)
        if (mesh->tri_patch[t] == IL_RAD_NO_PATCH)
            hc->occluders[hc->num_occluders++] = t;
    for (uint32_t p = 0; p < resolution; p++)
        hc->fold[p] = p < h ? h - 1 - p : p - h;
    for (uint32_t j = 0; j < mesh->num_patches; j++) {
        const il_rad_patch *pa = &mesh->patches[j];
        for (uint32_t k = 0; k < 4; k++) {
            il_vec3 v = mesh->positions[pa->v[k < pa->num_corners ? k : 0]];
            hc->patch_xyz[j * 12 + k * 3 + 0] = v.x;
            hc->patch_xyz[j * 12 + k * 3 + 1] = v.y;
            hc->patch_xyz[j * 12 + k * 3 + 2] = v.z;
        }
    }
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
    *out = hc;
    return IL_OK;
}

void il_hemicube_release(il_hemicube *hc)
{
    if (!hc)
        return;
    free(hc->top);
    free(hc->side);
    free(hc->fold);
    free(hc->patch_xyz);
    free(hc->occluders);
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
    size_t pixels = (size_t)hc->res * hc->res * 3;
    b->ids = il_malloc(pixels * sizeof *b->ids, err);
    b->depth = b->ids ? il_malloc(pixels * sizeof *b->depth, err) : NULL;
    b->scratch = b->depth ? il_calloc(hc->mesh->num_patches ? hc->mesh->num_patches : 1,
                                      sizeof *b->scratch, err)
                          : NULL;
    if (!b->scratch) {
        il_hemicube_buffers_release(b);
        return IL_ERR_MEMORY;
    }
    *out = b;
    return IL_OK;
}

void il_hemicube_buffers_release(il_hemicube_buffers *b)
{
    if (!b)
        return;
    free(b->ids);
    free(b->depth);
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

/* Scan-converts a convex polygon given in screen coordinates (sx, sy) with
 * 1/depth = wa*sx + wb*sy + wc, keeping the nearest id per pixel centre. */
static void raster(uint32_t *ids, float *depth, int width, int height, const float *sx,
                   const float *sy, int n, float wa, float wb, float wc, uint32_t id)
{
    float ymin = sy[0], ymax = sy[0];
    for (int k = 1; k < n; k++) {
        ymin = il_minf(ymin, sy[k]);
        ymax = il_maxf(ymax, sy[k]);
    }
    int y0 = (int)ceilf(ymin - 0.5f), y1 = (int)ceilf(ymax - 0.5f);
    if (y0 < 0)
        y0 = 0;
    if (y1 > height)
        y1 = height;
    for (int py = y0; py < y1; py++) {
        float yc = (float)py + 0.5f;
        float xl = INFINITY, xr = -INFINITY;
        for (int k = 0, l = n - 1; k < n; l = k++) {
            float ya = sy[l], yb = sy[k];
            if ((ya <= yc && yc < yb) || (yb <= yc && yc < ya)) {
                float x = sx[l] + (yc - ya) * (sx[k] - sx[l]) / (yb - ya);
                xl = il_minf(xl, x);
                xr = il_maxf(xr, x);
            }
        }
        if (!(xl < xr))
            continue;
        int x0 = (int)ceilf(xl - 0.5f), x1 = (int)ceilf(xr - 0.5f);
        if (x0 < 0)
            x0 = 0;
        if (x1 > width)
            x1 = width;
        uint32_t *row_id = ids + (size_t)py * (size_t)width;
        float *row_d = depth + (size_t)py * (size_t)width;
        float w = wa * ((float)x0 + 0.5f) + wb * yc + wc;
        for (int px = x0; px < x1; px++, w += wa) {
            if (w > row_d[px]) {
                row_d[px] = w;
                row_id[px] = id;
            }
        }
    }
}

/* Projects one planar convex polygon (local coordinates, plane N.x = k) onto
 * the five faces. */
static void draw_polygon(const il_hemicube *hc, il_hemicube_buffers *buf, const il_vec3 *loc,
                         int n, il_vec3 nrm, float k, float near, uint32_t id)
{
    int res = (int)hc->res, h = (int)hc->half;
    float fh = (float)h;
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
        float sx[IL_HC_MAX_VERTS], sy[IL_HC_MAX_VERTS];
        float voff = top ? 1.0f : 0.0f;
        for (int v = 0; v < m; v++) {
            float inv = 1.0f / poly[v].d;
            sx[v] = (poly[v].a * inv + 1.0f) * fh;
            sy[v] = (poly[v].b * inv + voff) * fh;
        }
        /* 1/d = NF.(u, v, 1) / k with u = sx/h - 1, v = sy/h - voff. */
        fvert nf = to_face(f, nrm.x, nrm.y, nrm.z);
        float ik = 1.0f / k;
        float wa = nf.a * ik / fh, wb = nf.b * ik / fh;
        float wc = (nf.d - nf.a - nf.b * voff) * ik;
        size_t offset = top ? 0 : (size_t)res * res + (size_t)(f - 1) * res * h;
        raster(buf->ids + offset, buf->depth + offset, res, top ? res : h, sx, sy, m, wa, wb, wc, id);
    }
}

/* Local coordinates of n world points in the frame (s, t, n) at c; false
 * when all lie on or below the base plane. */
static inline bool to_local(const float *xyz, int n, il_vec3 c, const il_frame *fr, il_vec3 *loc)
{
    bool above = false;
    for (int v = 0; v < n; v++) {
        il_vec3 d = v3(xyz[3 * v] - c.x, xyz[3 * v + 1] - c.y, xyz[3 * v + 2] - c.z);
        loc[v] = il_frame_to_local(fr, d);
        above |= loc[v].z > 0.0f;
    }
    return above;
}

void il_hemicube_row(const il_hemicube *hc, il_hemicube_buffers *buf, uint32_t i, il_ff_row *out)
{
    const il_rad_mesh *mesh = hc->mesh;
    out->count = 0;
    if (i >= mesh->num_patches)
        return;
    uint32_t res = hc->res, h = hc->half;
    size_t pixels = (size_t)res * res * 3;
    memset(buf->ids, 0xff, pixels * sizeof *buf->ids);
    memset(buf->depth, 0, pixels * sizeof *buf->depth);

    const il_rad_patch *pi = &mesh->patches[i];
    il_frame fr = il_frame_from_normal(pi->normal);
    il_vec3 c = pi->center;
    /* The near plane: far below the patch's size, far above float noise. */
    float near = 1e-4f * sqrtf(il_maxf(pi->area, 0.0f));
    if (!(near > 0.0f))
        near = 1e-8f;

    il_vec3 loc[4];
    for (uint32_t j = 0; j < mesh->num_patches; j++) {
        if (j == i)
            continue;
        int n = (int)mesh->patches[j].num_corners;
        if (!to_local(hc->patch_xyz + (size_t)j * 12, n, c, &fr, loc))
            continue;
        /* Plane N.x = k; the front faces the centre when k < 0 (CCW normal). */
        il_vec3 nrm = n == 4 ? v3_cross(v3_sub(loc[2], loc[0]), v3_sub(loc[3], loc[1]))
                             : v3_cross(v3_sub(loc[1], loc[0]), v3_sub(loc[2], loc[0]));
        float k = v3_dot(nrm, loc[0]);
        if (!(k < -near * v3_length(nrm)))
            continue; /* back-facing, or its plane passes through the centre */
        draw_polygon(hc, buf, loc, n, nrm, k, near, j);
    }
    for (uint32_t o = 0; o < hc->num_occluders; o++) {
        const uint32_t *tri = mesh->tri_indices + 3 * (size_t)hc->occluders[o];
        float xyz[9];
        for (int v = 0; v < 3; v++) {
            il_vec3 p = mesh->positions[tri[v]];
            xyz[3 * v] = p.x;
            xyz[3 * v + 1] = p.y;
            xyz[3 * v + 2] = p.z;
        }
        if (!to_local(xyz, 3, c, &fr, loc))
            continue;
        il_vec3 nrm = v3_cross(v3_sub(loc[1], loc[0]), v3_sub(loc[2], loc[0]));
        float k = v3_dot(nrm, loc[0]);
        if (!(fabsf(k) > near * v3_length(nrm)))
            continue; /* edge-on: covers no pixel */
        draw_polygon(hc, buf, loc, 3, nrm, k, near, IL_HC_NONE);
    }

    /* Sum the delta form factors per item through the symmetry folds; runs
     * of one id along a row are summed locally first (fewer scattered adds). */
    float *acc = buf->scratch;
    const uint32_t *fold = hc->fold;
    const uint32_t *ids = buf->ids;
    uint32_t run_id = IL_HC_NONE;
    float run = 0.0f;
#define IL_HC_FLUSH(next)                                                               \
    do {                                                                                \
        if (run_id != IL_HC_NONE) {                                                     \
            if (acc[run_id] == 0.0f)                                                    \
                out->index[out->count++] = run_id;                                      \
            acc[run_id] += run;                                                         \
        }                                                                               \
        run_id = (next);                                                                \
        run = 0.0f;                                                                     \
    } while (0)
    for (uint32_t py = 0; py < res; py++) {
        uint32_t fb = fold[py];
        const uint32_t *row = ids + (size_t)py * res;
        for (uint32_t px = 0; px < res; px++) {
            uint32_t id = row[px];
            if (id != run_id)
                IL_HC_FLUSH(id);
            if (id == IL_HC_NONE)
                continue;
            uint32_t fa = fold[px];
            uint32_t hi = fa > fb ? fa : fb, lo = fa > fb ? fb : fa;
            run += hc->top[hi * (hi + 1) / 2 + lo];
        }
    }
    for (uint32_t f = 0; f < 4; f++) {
        const uint32_t *side = ids + (size_t)res * res + (size_t)f * res * h;
        for (uint32_t py = 0; py < h; py++) {
            const uint32_t *row = side + (size_t)py * res;
            const float *dff = hc->side + (size_t)py * h;
            for (uint32_t px = 0; px < res; px++) {
                uint32_t id = row[px];
                if (id != run_id)
                    IL_HC_FLUSH(id);
                if (id != IL_HC_NONE)
                    run += dff[fold[px]];
            }
        }
    }
    IL_HC_FLUSH(IL_HC_NONE);
#undef IL_HC_FLUSH
    il_ff_row_compact(acc, mesh->num_patches, 1.0f, out);
}
