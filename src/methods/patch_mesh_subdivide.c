/* Radiosity meshing, step 2: each element (quad or triangle) becomes a grid
 * of patches.
 *
 * Uniform levels (settings->subdivisions = L > 0): L midpoint splits of a
 * quad into 2x2 quads, or of a triangle into 4 triangles, which is exactly the
 * 2^L x 2^L bilinear (quad) or barycentric (triangle) grid, so it is built
 * in one go.  Otherwise by patch size s: a quad gets nu x nv cells with
 * nu = ceil(longer of the two u edges / s), nv likewise, and a triangle
 * n^2 triangles with n = ceil(longest edge / s).
 *
 * Points on an element's boundary are computed by il_patch_edge_point from the
 * edge's two corners in a canonical order, so two elements of one surface
 * that share an edge weld their common points exactly.  Where neighbouring
 * elements get different counts along a shared edge (patch-size meshing of
 * differently sized elements), the points that do not coincide leave
 * T-junctions; they are allowed: vertices only carry the interpolated
 * radiance, and the patches still tile the surface without gaps or overlap. */
#include <math.h>

#include "methods/patch_mesh_internal.h"

il_vec3 il_patch_edge_point(uint32_t ida, il_vec3 pa, uint32_t idb, il_vec3 pb, uint32_t k,
                          uint32_t n)
{
    if (idb < ida) {
        il_vec3 tp = pa;
        pa = pb;
        pb = tp;
        k = n - k;
    }
    if (k == 0)
        return pa;
    if (k == n)
        return pb;
    /* k/n is correctly rounded, so equal fractions (1/2, 2/4) give equal points. */
    double t = (double)k / (double)n;
    return v3((float)(pa.x + ((double)pb.x - pa.x) * t), (float)(pa.y + ((double)pb.y - pa.y) * t),
              (float)(pa.z + ((double)pb.z - pa.z) * t));
}

static double elen(il_vec3 a, il_vec3 b)
{
    double x = (double)a.x - b.x, y = (double)a.y - b.y, z = (double)a.z - b.z;
    return sqrt(x * x + y * y + z * z);
}

static double cells(double len, double size)
{
    double n = ceil(len / size);
    return n >= 1.0 ? n : (n != n ? n : 1.0); /* NaN stays NaN for the caller's check */
}

double il_patch_elem_grid(const il_patch_elem *e, const il_patch_sizing *s, double *nu, double *nv)
{
    if (s->subdivisions > 0) {
        *nu = *nv = ldexp(1.0, (int)(s->subdivisions > 1000 ? 1000 : s->subdivisions));
    } else if (e->num_corners == 4) {
        const il_vec3 *p = e->p;
        *nu = cells(fmax(elen(p[0], p[1]), elen(p[3], p[2])), s->patch_size);
        *nv = cells(fmax(elen(p[0], p[3]), elen(p[1], p[2])), s->patch_size);
    } else {
        const il_vec3 *p = e->p;
        double longest = fmax(elen(p[0], p[1]), fmax(elen(p[1], p[2]), elen(p[2], p[0])));
        *nu = *nv = cells(longest, s->patch_size);
    }
    return *nu * *nv;
}

/* The quad's bilinear map at (u, v), in double: (1-u)(1-v) p0 + u(1-v) p1
 * + uv p2 + (1-u)v p3; on a planar quad every point stays in the plane. */
static il_vec3 bilinear(const il_vec3 p[4], double u, double v)
{
    double w0 = (1.0 - u) * (1.0 - v), w1 = u * (1.0 - v), w2 = u * v, w3 = (1.0 - u) * v;
    return v3((float)(w0 * p[0].x + w1 * p[1].x + w2 * p[2].x + w3 * p[3].x),
              (float)(w0 * p[0].y + w1 * p[1].y + w2 * p[2].y + w3 * p[3].y),
              (float)(w0 * p[0].z + w1 * p[1].z + w2 * p[2].z + w3 * p[3].z));
}

static il_status emit_quad(il_patch_builder *b, const il_patch_elem *e, uint32_t nu, uint32_t nv,
                           uint32_t *g)
{
    const uint32_t *id = e->id;
    const il_vec3 *p = e->p;
    size_t row = (size_t)nu + 1;
    for (uint32_t j = 0; j <= nv; j++)
        for (uint32_t i = 0; i <= nu; i++) {
            il_vec3 q;
            if (j == 0)
                q = il_patch_edge_point(id[0], p[0], id[1], p[1], i, nu);
            else if (j == nv)
                q = il_patch_edge_point(id[3], p[3], id[2], p[2], i, nu);
            else if (i == 0)
                q = il_patch_edge_point(id[0], p[0], id[3], p[3], j, nv);
            else if (i == nu)
                q = il_patch_edge_point(id[1], p[1], id[2], p[2], j, nv);
            else
                q = bilinear(p, (double)i / nu, (double)j / nv);
            uint32_t vid = il_patch_builder_vertex(b, e->surface, q);
            if (vid == UINT32_MAX)
                return IL_ERR_MEMORY;
            g[j * row + i] = vid;
        }
    uint32_t ncand = e->src[0] == e->src[1] ? 1 : 2;
    for (uint32_t j = 0; j < nv; j++)
        for (uint32_t i = 0; i < nu; i++) {
            const uint32_t v[4] = {g[j * row + i], g[j * row + i + 1], g[(j + 1) * row + i + 1],
                                   g[(j + 1) * row + i]};
            il_status st = il_patch_builder_patch(b, e->surface, 4, v, e->src, ncand);
            if (st != IL_OK)
                return st;
        }
    return IL_OK;
}

static il_status emit_triangle(il_patch_builder *b, const il_patch_elem *e, uint32_t n, uint32_t *g)
{
    const uint32_t *id = e->id;
    const il_vec3 *p = e->p;
    size_t row = (size_t)n + 1;
    for (uint32_t j = 0; j <= n; j++)
        for (uint32_t i = 0; i + j <= n; i++) {
            il_vec3 q;
            if (j == 0)
                q = il_patch_edge_point(id[0], p[0], id[1], p[1], i, n);
            else if (i == 0)
                q = il_patch_edge_point(id[0], p[0], id[2], p[2], j, n);
            else if (i + j == n)
                q = il_patch_edge_point(id[1], p[1], id[2], p[2], j, n);
            else {
                /* Barycentric grid point (i/n, j/n) of corners 1 and 2. */
                double b1 = (double)i / n, b2 = (double)j / n, b0 = 1.0 - b1 - b2;
                q = v3((float)(b0 * p[0].x + b1 * p[1].x + b2 * p[2].x),
                       (float)(b0 * p[0].y + b1 * p[1].y + b2 * p[2].y),
                       (float)(b0 * p[0].z + b1 * p[1].z + b2 * p[2].z));
            }
            uint32_t vid = il_patch_builder_vertex(b, e->surface, q);
            if (vid == UINT32_MAX)
                return IL_ERR_MEMORY;
            g[j * row + i] = vid;
        }
    for (uint32_t j = 0; j < n; j++)
        for (uint32_t i = 0; i + j < n; i++) {
            /* The upright triangle at (i, j), then the inverted one beside
             * it; both keep the element's counter-clockwise order. */
            const uint32_t up[4] = {g[j * row + i], g[j * row + i + 1], g[(j + 1) * row + i], 0};
            il_status st = il_patch_builder_patch(b, e->surface, 3, up, e->src, 1);
            if (st != IL_OK)
                return st;
            if (i + j + 1 < n) {
                const uint32_t down[4] = {g[j * row + i + 1], g[(j + 1) * row + i + 1],
                                          g[(j + 1) * row + i], 0};
                if ((st = il_patch_builder_patch(b, e->surface, 3, down, e->src, 1)) != IL_OK)
                    return st;
            }
        }
    return IL_OK;
}

il_status il_patch_elem_emit(il_patch_builder *b, const il_patch_elem *e, uint32_t nu, uint32_t nv,
                           uint32_t *scratch)
{
    return e->num_corners == 4 ? emit_quad(b, e, nu, nv, scratch)
                               : emit_triangle(b, e, nu, scratch);
}
