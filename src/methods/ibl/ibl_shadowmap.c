/* Shadow maps for the directional lights (Williams 1978, "Casting Curved
 * Shadows on Curved Surfaces"), the visibility test of Kemmer 2005's GPU
 * renderer, as an alternative to exact shadow rays.
 *
 * One orthographic depth map per light covers the scene's bounding sphere
 * seen from the light's direction.  It is built by rasterising every
 * triangle of the scene (our own scan conversion: texel centres inside the
 * projected triangle, edges inclusive so that the triangles of a mesh leave
 * no gap), keeping per texel the surface nearest the light.  The lookup is
 * percentage-closer filtering (Reeves, Salesin & Cook 1987): the fraction of
 * taps x taps tests around the point whose surface is not nearer the light
 * than the point, each test bilinear between its four nearest texels so
 * that the filter is centred on the point.  Each texel is compared with the
 * receiver's own plane extrapolated to the texel's centre (receiver-plane
 * depth bias, Isidoro 2006, "Shadow Mapping: GPU-based Tips and
 * Techniques"), so flat and gently curved receivers do not shadow
 * themselves, plus a constant bias (a fraction of the scene's diagonal)
 * for curvature and rounding. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/ibl/ibl.h"

/* Receiver-plane slopes are clamped to this (a plane within 0.06 degrees
 * of the light's direction, whose cosine makes its light negligible), only
 * to keep the arithmetic finite.  A low sun needs large slopes: at 2.6
 * degrees of elevation (Poly Haven's Pedestrian Overpass) a floor's depth
 * changes by 22 texels per texel. */
#define IL_IBL_MAX_SLOPE 1000.0f

il_status il_ibl_shadow_maps_alloc(il_ibl_shadow_maps *sm, uint32_t count, uint32_t size,
                                   uint32_t taps, float bias, il_error *err)
{
    memset(sm, 0, sizeof *sm);
    sm->maps = il_calloc(count ? count : 1, sizeof(il_ibl_shadow_map), err);
    sm->memory = il_malloc((size_t)(count ? count : 1) * size * size * sizeof(float), err);
    if (!sm->maps || !sm->memory) {
        il_ibl_shadow_maps_free(sm);
        return IL_ERR_MEMORY;
    }
    sm->count = count;
    sm->size = size;
    sm->taps = taps;
    sm->bias = bias;
    for (uint32_t k = 0; k < count; k++)
        sm->maps[k].depth = sm->memory + (size_t)k * size * size;
    return IL_OK;
}

void il_ibl_shadow_maps_free(il_ibl_shadow_maps *sm)
{
    free(sm->maps);
    free(sm->memory);
    memset(sm, 0, sizeof *sm);
}

typedef struct proj { float x, y, z; } proj;

/* A world point in the map's texel coordinates (x, y) and depth z. */
static inline proj project(const il_ibl_shadow_map *m, il_vec3 p)
{
    return (proj){(v3_dot(p, m->du) - m->u0) * m->inv_texel,
                  (v3_dot(p, m->dv) - m->v0) * m->inv_texel, v3_dot(p, m->dz)};
}

/* Scan-converts one projected triangle into the map: texel (i, j) has its
 * centre at (i + 0.5, j + 0.5); the depth there is interpolated from the
 * corners (orthographic, so linearly) and the largest kept.  Each row's
 * span is solved from the three edge functions (linear in x) instead of
 * testing every texel of the bounding box. */
static void raster_triangle(il_ibl_shadow_map *m, proj a, proj b, proj c)
{
    int n = (int)m->size;
    float fx0 = il_minf(a.x, il_minf(b.x, c.x)), fx1 = il_maxf(a.x, il_maxf(b.x, c.x));
    float fy0 = il_minf(a.y, il_minf(b.y, c.y)), fy1 = il_maxf(a.y, il_maxf(b.y, c.y));
    /* Texel centres inside the bounding box: most small triangles have none. */
    float cx0 = ceilf(fx0 - 0.5f), cx1 = floorf(fx1 - 0.5f);
    float cy0 = ceilf(fy0 - 0.5f), cy1 = floorf(fy1 - 0.5f);
    if (!(cx0 <= cx1 && cy0 <= cy1) || cx1 < 0.0f || cy1 < 0.0f || cx0 > (float)(n - 1) ||
        cy0 > (float)(n - 1))
        return;
    float area = (b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x);
    if (!(fabsf(area) > 1e-12f))
        return; /* seen edge-on: covers no area */
    int x0 = cx0 < 0.0f ? 0 : (int)cx0, x1 = cx1 > (float)(n - 1) ? n - 1 : (int)cx1;
    int y0 = cy0 < 0.0f ? 0 : (int)cy0, y1 = cy1 > (float)(n - 1) ? n - 1 : (int)cy1;
    float inv = 1.0f / area;
    /* Barycentric weights of b and c at q = a + (px, py), ratios of 2D cross
     * products: wb = (q-a) x (c-a) / area, wc = (b-a) x (q-a) / area;
     * wa = 1 - wb - wc.  All three are affine in x along a row. */
    float wb_x = (c.y - a.y) * inv, wb_y = -(c.x - a.x) * inv;
    float wc_x = -(b.y - a.y) * inv, wc_y = (b.x - a.x) * inv;
    float wa_x = -wb_x - wc_x;
    float dzb = b.z - a.z, dzc = c.z - a.z;
    float z_x = wb_x * dzb + wc_x * dzc;
    /* A small tolerance keeps texel centres on shared edges covered by
     * both triangles despite rounding. */
    const float eps = -1e-6f;
    for (int y = y0; y <= y1; y++) {
        float py = (float)y + 0.5f - a.y;
        float px0 = (float)x0 + 0.5f - a.x;
        /* The weights at the row's first texel centre, and the span of x
         * (offsets from x0) where all three stay >= eps. */
        float wb0 = wb_x * px0 + wb_y * py, wc0 = wc_x * px0 + wc_y * py;
        float w0[3] = {1.0f - wb0 - wc0, wb0, wc0}, wx[3] = {wa_x, wb_x, wc_x};
        float lo = 0.0f, hi = (float)(x1 - x0);
        for (int k = 0; k < 3 && lo <= hi; k++) {
            if (wx[k] > 0.0f)
                lo = il_maxf(lo, ceilf((eps - w0[k]) / wx[k]));
            else if (wx[k] < 0.0f)
                hi = il_minf(hi, floorf((eps - w0[k]) / wx[k]));
            else if (w0[k] < eps)
                hi = -1.0f;
        }
        if (lo > hi)
            continue;
        float *row = m->depth + (size_t)y * m->size;
        float z = a.z + wb0 * dzb + wc0 * dzc;
        for (int x = x0 + (int)lo; x <= x0 + (int)hi; x++) {
            float zx = z + z_x * (float)(x - x0);
            if (zx > row[x])
                row[x] = zx;
        }
    }
}

void il_ibl_shadow_map_build(const il_scene *scene, il_ibl_shadow_map *m, uint32_t size,
                             il_vec3 dir)
{
    il_frame f = il_frame_from_normal(dir);
    m->du = f.s;
    m->dv = f.t;
    m->dz = dir;
    m->size = size;
    float r = scene->scene_radius > 0.0f ? scene->scene_radius : 1.0f;
    /* A hair wider than the bounding sphere so its rim is inside the map. */
    r *= 1.001f;
    m->texel = 2.0f * r / (float)size;
    m->inv_texel = (float)size / (2.0f * r);
    m->u0 = v3_dot(scene->scene_center, m->du) - r;
    m->v0 = v3_dot(scene->scene_center, m->dv) - r;
    for (size_t k = 0; k < (size_t)size * size; k++)
        m->depth[k] = -INFINITY;
    for (uint32_t i = 0; i < scene->num_meshes; i++) {
        const il_mesh *mesh = &scene->meshes[i];
        for (uint32_t t = 0; t < mesh->num_triangles; t++) {
            const il_tri_geom *g = &mesh->geom[t];
            raster_triangle(m, project(m, g->p0), project(m, g->p1), project(m, g->p2));
        }
    }
}

float il_ibl_shadow_map_lookup(const il_ibl_shadow_maps *sm, const il_ibl_shadow_map *m,
                               const il_ibl_vertex *v)
{
    proj p = project(m, v->org);
    /* The receiver plane (normal g) as depth over the map: z(p + a du + b dv)
     * = z_p + gu a + gv b with gu = -(g.du)/(g.dz), gv = -(g.dv)/(g.dz);
     * per texel, times the texel size.  g.dz > 0: the caller only asks
     * for lights above the surface. */
    float gz = il_maxf(v3_dot(v->g, m->dz), 1e-6f);
    float gu = il_clampf(-v3_dot(v->g, m->du) / gz, -IL_IBL_MAX_SLOPE, IL_IBL_MAX_SLOPE) * m->texel;
    float gv = il_clampf(-v3_dot(v->g, m->dv) / gz, -IL_IBL_MAX_SLOPE, IL_IBL_MAX_SLOPE) * m->texel;
    /* taps x taps tests at p + (a, b) texels, a, b in -half..half, each
     * bilinear between its four nearest texel centres (the hardware's
     * filtered comparison).  The offsets are whole texels, so all taps share
     * the fractions fx, fy, and the taps together weigh a (taps+1)^2 block
     * of texels: columns (1-fx), 1, ..., 1, fx and rows likewise.  Centred
     * on p itself, not on its texel's centre: otherwise the shadow edge
     * moves with where p lies in its texel, by up to half a texel. */
    int n = (int)m->size, taps = (int)sm->taps, half = taps / 2;
    float sx = p.x - 0.5f, sy = p.y - 0.5f;
    float fi = floorf(sx), fj = floorf(sy);
    float fx = sx - fi, fy = sy - fj;
    int i0 = (int)fi - half, j0 = (int)fj - half;
    /* The receiver's depth at texel (i, j)'s centre, plus the bias:
     * base + gu i + gv j. */
    float base = p.z + gu * (0.5f - p.x) + gv * (0.5f - p.y) + sm->bias;
    float wx[IL_IBL_MAX_PCF + 1], wy[IL_IBL_MAX_PCF + 1];
    for (int k = 0; k <= taps; k++) {
        wx[k] = k == 0 ? 1.0f - fx : (k == taps ? fx : 1.0f);
        wy[k] = k == 0 ? 1.0f - fy : (k == taps ? fy : 1.0f);
    }
    float lit = 0.0f;
    if (i0 >= 0 && j0 >= 0 && i0 + taps < n && j0 + taps < n) {
        /* The whole block inside the map: no bounds to check. */
        for (int jj = 0; jj <= taps; jj++) {
            const float *row = m->depth + (size_t)(j0 + jj) * m->size + i0;
            float z = base + gv * (float)(j0 + jj) + gu * (float)i0;
            float row_lit = 0.0f;
            for (int ii = 0; ii <= taps; ii++)
                row_lit += row[ii] <= z + gu * (float)ii ? wx[ii] : 0.0f;
            lit += wy[jj] * row_lit;
        }
    } else {
        for (int jj = 0; jj <= taps; jj++) {
            int j = j0 + jj;
            float row_lit = 0.0f;
            for (int ii = 0; ii <= taps; ii++) {
                int i = i0 + ii;
                /* Outside the map lies nothing (it covers the scene's bounds). */
                bool free = i < 0 || j < 0 || i >= n || j >= n ||
                            m->depth[(size_t)j * m->size + i] <= base + gv * (float)j + gu * (float)i;
                row_lit += free ? wx[ii] : 0.0f;
            }
            lit += wy[jj] * row_lit;
        }
    }
    return lit / (float)(taps * taps);
}
