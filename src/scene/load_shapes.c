/* Built-in shapes for JSON scenes: quad, box, UV sphere. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "core/vec.h"
#include "scene/loader.h"

static il_status shape_alloc(il_shape_mesh *m, uint32_t nv, uint32_t nt, bool normals,
                             il_error *err)
{
    memset(m, 0, sizeof *m);
    m->num_vertices = nv;
    m->num_triangles = nt;
    m->positions = il_malloc((size_t)nv * 3 * sizeof(float), err);
    m->uvs = il_malloc((size_t)nv * 2 * sizeof(float), err);
    m->indices = il_malloc((size_t)nt * 3 * sizeof(uint32_t), err);
    if (normals)
        m->normals = il_malloc((size_t)nv * 3 * sizeof(float), err);
    if (!m->positions || !m->uvs || !m->indices || (normals && !m->normals)) {
        il_shape_free(m);
        return IL_ERR_MEMORY;
    }
    return IL_OK;
}

void il_shape_free(il_shape_mesh *m)
{
    free(m->positions);
    free(m->normals);
    free(m->uvs);
    free(m->indices);
    memset(m, 0, sizeof *m);
}

void il_shape_flip(il_shape_mesh *m)
{
    for (uint32_t t = 0; t < m->num_triangles; t++) {
        uint32_t *tri = m->indices + 3 * (size_t)t;
        uint32_t k = tri[1];
        tri[1] = tri[2];
        tri[2] = k;
    }
    if (m->normals)
        for (size_t i = 0; i < 3 * (size_t)m->num_vertices; i++)
            m->normals[i] = -m->normals[i];
}

/* One rectangle: corner c, edges u and v (counter-clockwise seen from u x v). */
static void put_rect(il_shape_mesh *m, uint32_t *vi, uint32_t *ti, il_vec3 c, il_vec3 u, il_vec3 v)
{
    uint32_t b = *vi;
    il_vec3 p[4] = {c, v3_add(c, u), v3_add(v3_add(c, u), v), v3_add(c, v)};
    const float uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int k = 0; k < 4; k++) {
        m->positions[3 * (b + k)] = p[k].x;
        m->positions[3 * (b + k) + 1] = p[k].y;
        m->positions[3 * (b + k) + 2] = p[k].z;
        m->uvs[2 * (b + k)] = uv[k][0];
        m->uvs[2 * (b + k) + 1] = uv[k][1];
    }
    const uint32_t tri[6] = {b, b + 1, b + 2, b, b + 2, b + 3};
    memcpy(m->indices + 3 * (size_t)*ti, tri, sizeof tri);
    *vi += 4;
    *ti += 2;
}

il_status il_shape_quad(float sx, float sz, il_shape_mesh *out, il_error *err)
{
    il_status s = shape_alloc(out, 4, 2, false, err);
    if (s != IL_OK)
        return s;
    uint32_t vi = 0, ti = 0;
    /* u = +z, v = +x: u x v = +y. */
    put_rect(out, &vi, &ti, v3(-0.5f * sx, 0, -0.5f * sz), v3(0, 0, sz), v3(sx, 0, 0));
    return IL_OK;
}

il_status il_shape_box(float sx, float sy, float sz, il_shape_mesh *out, il_error *err)
{
    il_status s = shape_alloc(out, 24, 12, false, err);
    if (s != IL_OK)
        return s;
    float x = 0.5f * sx, y = 0.5f * sy, z = 0.5f * sz;
    uint32_t vi = 0, ti = 0;
    put_rect(out, &vi, &ti, v3(x, -y, -z), v3(0, sy, 0), v3(0, 0, sz));   /* +x */
    put_rect(out, &vi, &ti, v3(-x, -y, -z), v3(0, 0, sz), v3(0, sy, 0));  /* -x */
    put_rect(out, &vi, &ti, v3(-x, y, -z), v3(0, 0, sz), v3(sx, 0, 0));   /* +y */
    put_rect(out, &vi, &ti, v3(-x, -y, -z), v3(sx, 0, 0), v3(0, 0, sz));  /* -y */
    put_rect(out, &vi, &ti, v3(-x, -y, z), v3(sx, 0, 0), v3(0, sy, 0));   /* +z */
    put_rect(out, &vi, &ti, v3(-x, -y, -z), v3(0, sy, 0), v3(sx, 0, 0));  /* -z */
    return IL_OK;
}

il_status il_shape_sphere(float radius, uint32_t segments, il_shape_mesh *out, il_error *err)
{
    uint32_t ns = segments < 3 ? 3 : segments;
    uint32_t nr = ns / 2 < 2 ? 2 : ns / 2; /* rings from pole to pole */
    /* (ns+1) columns (a seam) x (nr+1) rows; the pole rows get one triangle per
     * segment, the others two. */
    uint32_t nv = (ns + 1) * (nr + 1);
    uint32_t nt = 2 * ns * (nr - 1);
    il_status s = shape_alloc(out, nv, nt, true, err);
    if (s != IL_OK)
        return s;
    for (uint32_t r = 0; r <= nr; r++) {
        float theta = IL_PI * (float)r / (float)nr; /* from +y */
        for (uint32_t c = 0; c <= ns; c++) {
            float phi = 2.0f * IL_PI * (float)c / (float)ns;
            il_vec3 n = v3(sinf(theta) * sinf(phi), cosf(theta), sinf(theta) * cosf(phi));
            if (r == 0 || r == nr)
                n = v3(0, r == 0 ? 1.0f : -1.0f, 0);
            size_t v = (size_t)r * (ns + 1) + c;
            out->positions[3 * v] = radius * n.x;
            out->positions[3 * v + 1] = radius * n.y;
            out->positions[3 * v + 2] = radius * n.z;
            out->normals[3 * v] = n.x;
            out->normals[3 * v + 1] = n.y;
            out->normals[3 * v + 2] = n.z;
            out->uvs[2 * v] = (float)c / (float)ns;
            out->uvs[2 * v + 1] = 1.0f - (float)r / (float)nr;
        }
    }
    uint32_t t = 0;
    for (uint32_t r = 0; r < nr; r++)
        for (uint32_t c = 0; c < ns; c++) {
            uint32_t a = r * (ns + 1) + c, b = a + 1;          /* upper row */
            uint32_t d = (r + 1) * (ns + 1) + c, e = d + 1;    /* lower row */
            /* Seen from outside, phi grows to the right (towards +x at the front). */
            if (r != 0) {
                const uint32_t tri[3] = {a, d, b};
                memcpy(out->indices + 3 * (size_t)t++, tri, sizeof tri);
            }
            if (r != nr - 1) {
                const uint32_t tri[3] = {b, d, e};
                memcpy(out->indices + 3 * (size_t)t++, tri, sizeof tri);
            }
        }
    return IL_OK;
}
