/* Open or closed meshes; see mesh_open.h. */
#include "scene/mesh_open.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* A vertex's position on a grid of a millionth of the mesh's size, so that
 * corners computed twice (a sphere's poles: r sin(pi) is not 0) match. */
typedef struct placed {
    int64_t p[3];
    uint32_t v;
} placed;

static int by_position(const void *a, const void *b)
{
    const int64_t *p = ((const placed *)a)->p, *q = ((const placed *)b)->p;
    for (int k = 0; k < 3; k++)
        if (p[k] != q[k])
            return p[k] < q[k] ? -1 : 1;
    return 0;
}

static int by_value(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

il_status il_mesh_is_open(const float *positions, uint32_t num_vertices, const uint32_t *indices,
                          uint32_t num_triangles, bool *open, il_error *err)
{
    *open = num_triangles > 0;
    if (num_triangles == 0 || num_vertices == 0)
        return IL_OK;
    placed *order = il_malloc((size_t)num_vertices * sizeof *order, err);
    uint32_t *canon = il_malloc((size_t)num_vertices * sizeof *canon, err);
    uint64_t *edges = il_malloc(3 * (size_t)num_triangles * sizeof *edges, err);
    if (!order || !canon || !edges) {
        free(order);
        free(canon);
        free(edges);
        return IL_ERR_MEMORY;
    }
    /* One id per distinct position: the first vertex of its run in sorted order. */
    double lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < 3 * (size_t)num_vertices; i++) {
        lo[i % 3] = fmin(lo[i % 3], positions[i]);
        hi[i % 3] = fmax(hi[i % 3], positions[i]);
    }
    double size = fmax(fmax(hi[0] - lo[0], hi[1] - lo[1]), hi[2] - lo[2]);
    double cell = size > 0.0 && isfinite(size) ? size * 1e-6 : 1.0;
    for (uint32_t v = 0; v < num_vertices; v++) {
        order[v].v = v;
        for (int k = 0; k < 3; k++)
            order[v].p[k] = (int64_t)llround((positions[3 * (size_t)v + k] - lo[k]) / cell);
    }
    qsort(order, num_vertices, sizeof *order, by_position);
    for (uint32_t i = 0; i < num_vertices; i++)
        canon[order[i].v] = i > 0 && by_position(&order[i - 1], &order[i]) == 0 ? canon[order[i - 1].v]
                                                                                : order[i].v;
    /* Every edge as (smaller id, larger id); a border edge appears once. */
    size_t n = 0;
    for (uint32_t t = 0; t < num_triangles; t++) {
        for (int k = 0; k < 3; k++) {
            uint32_t a = canon[indices[3 * (size_t)t + k]], b = canon[indices[3 * (size_t)t + (k + 1) % 3]];
            if (a == b)
                continue;                 /* a degenerate triangle's collapsed edge */
            edges[n++] = a < b ? (uint64_t)a << 32 | b : (uint64_t)b << 32 | a;
        }
    }
    qsort(edges, n, sizeof *edges, by_value);
    bool border = false;
    for (size_t i = 0; i < n && !border;) {
        size_t j = i;
        while (j < n && edges[j] == edges[i])
            j++;
        border = j - i == 1;
        i = j;
    }
    *open = border;
    free(order);
    free(canon);
    free(edges);
    return IL_OK;
}
