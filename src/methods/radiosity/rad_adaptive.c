/* Which patches adaptive subdivision splits: those at a sharp change of
 * radiance, found by comparing each patch with its neighbours (Cohen et al.
 * 1986, "An efficient radiosity approach for realistic image synthesis",
 * IEEE CG&A 6(3): substructuring where the radiosity gradient between
 * adjacent elements exceeds a threshold; Cohen & Wallace 1993, section 8.2).
 *
 * Neighbours are the patches sharing a vertex with it.  Vertices are never
 * shared across surfaces, so neighbours always lie in the same surface. */
#include <stdlib.h>

#include "methods/radiosity/rad.h"

/* Vertex -> patch adjacency in compressed rows: the patches around vertex v
 * are list[first[v] .. first[v+1]). */
typedef struct vertex_patches {
    uint32_t *first;
    uint32_t *list;
} vertex_patches;

static bool build_adjacency(const il_patch_mesh *mesh, vertex_patches *adj)
{
    uint32_t nv = mesh->num_vertices;
    adj->first = calloc((size_t)nv + 1, sizeof *adj->first);
    size_t refs = 0;
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        refs += mesh->patches[i].num_corners;
    adj->list = malloc((refs ? refs : 1) * sizeof *adj->list);
    if (!adj->first || !adj->list) {
        free(adj->first);
        free(adj->list);
        return false;
    }
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        for (uint32_t c = 0; c < mesh->patches[i].num_corners; c++)
            adj->first[mesh->patches[i].v[c] + 1]++;
    for (uint32_t v = 0; v < nv; v++)
        adj->first[v + 1] += adj->first[v];
    /* Fill with a moving cursor per vertex (first[v] advances), then shift
     * back: afterwards first[v] is the start of v's row again. */
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        for (uint32_t c = 0; c < mesh->patches[i].num_corners; c++)
            adj->list[adj->first[mesh->patches[i].v[c]]++] = i;
    for (uint32_t v = nv; v > 0; v--)
        adj->first[v] = adj->first[v - 1];
    adj->first[0] = 0;
    return true;
}

uint32_t il_rad_mark_split(const il_patch_mesh *mesh, const il_rad_solution *sol, float threshold,
                           bool *split)
{
    uint32_t np = mesh->num_patches;
    for (uint32_t i = 0; i < np; i++)
        split[i] = false;
    vertex_patches adj;
    /* The contract has no error path: without memory for the adjacency
     * nothing is marked, so the caller keeps its current mesh. */
    if (np == 0 || !build_adjacency(mesh, &adj))
        return 0;

    float brightest = 0.0f;
    for (uint32_t i = 0; i < np; i++)
        brightest = il_maxf(brightest, il_luminance(sol->radiance[i]));
    /* The floor keeps a relative test meaningful in the dark: patches that
     * are both nearly black are not split over noise. */
    float floor = 1e-6f * brightest;

    uint32_t marked = 0;
    for (uint32_t i = 0; i < np; i++) {
        const il_patch *p = &mesh->patches[i];
        float li = il_luminance(sol->radiance[i]);
        for (uint32_t c = 0; c < p->num_corners && !split[i]; c++) {
            uint32_t v = p->v[c];
            for (uint32_t k = adj.first[v]; k < adj.first[v + 1]; k++) {
                uint32_t j = adj.list[k];
                if (j == i)
                    continue;
                float lj = il_luminance(sol->radiance[j]);
                float scale = il_maxf(il_maxf(li, lj), floor);
                if (fabsf(li - lj) > threshold * scale) {
                    split[i] = true;
                    break;
                }
            }
        }
        marked += split[i];
    }
    free(adj.first);
    free(adj.list);
    return marked;
}
