/* Per-vertex radiance for display: each vertex takes the area-weighted mean
 * of the radiance of the patches around it (Cohen & Wallace, "Radiosity and
 * Realistic Image Synthesis", 1993, section 9.2.1: nodal values averaged from
 * the adjoining elements, weighted by area).  The mesh never shares a vertex
 * between two surfaces, so the mean never mixes a wall with its neighbour. */
#include <stdlib.h>

#include "methods/patch_mesh.h"

void il_patch_vertex_radiance(const il_patch_mesh *mesh, const il_vec3 *patch_radiance,
                            il_vec3 *out)
{
    uint32_t nv = mesh->num_vertices;
    for (uint32_t v = 0; v < nv; v++)
        out[v] = v3s(0.0f);
    /* The sum of the areas around each vertex.  The contract has no error
     * path: without memory for it (num_vertices floats) every vertex takes
     * the radiance of the last patch that uses it instead (flat shading). */
    float *weight = calloc(nv ? nv : 1, sizeof *weight);
    for (uint32_t i = 0; i < mesh->num_patches; i++) {
        const il_patch *p = &mesh->patches[i];
        for (uint32_t c = 0; c < p->num_corners; c++) {
            uint32_t v = p->v[c];
            if (weight) {
                out[v] = v3_fma(out[v], patch_radiance[i], p->area);
                weight[v] += p->area;
            } else {
                out[v] = patch_radiance[i];
            }
        }
    }
    if (!weight)
        return;
    /* Vertices no patch uses (mirror and glass triangles) stay zero. */
    for (uint32_t v = 0; v < nv; v++) {
        float w = weight[v];
        out[v] = w > 0.0f ? v3(out[v].x / w, out[v].y / w, out[v].z / w) : v3s(0.0f);
    }
    free(weight);
}
