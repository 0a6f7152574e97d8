/* The leaves of the quadtrees as an il_patch_mesh, so the shared per-vertex
 * averaging, camera pass and bake work unchanged: level by level, every
 * patch whose element has children is split by il_patch_mesh_refine, which
 * puts a split patch's 4 children where it was, in the order of
 * il_hr_children (both follow patch_mesh.c's split_patch).  The elements
 * are carried along in the same order, so patch i of the final mesh is
 * leaf element i. */
#include <stdlib.h>

#include "core/error.h"
#include "methods/hr/hr.h"

il_status il_hr_output_mesh(const il_hr_solver *s, il_patch_mesh **mesh_out,
                            il_vec3 **patch_radiance_out, il_error *err)
{
    *mesh_out = NULL;
    *patch_radiance_out = NULL;
    const il_patch_mesh *cur = s->mesh;
    uint32_t n = s->num_roots;
    const il_hr_elem **elems = il_malloc((size_t)(n ? n : 1u) * sizeof *elems, err);
    if (!elems)
        return IL_ERR_MEMORY;
    for (uint32_t i = 0; i < n; i++)
        elems[i] = &s->roots[i];
    il_status st = IL_OK;
    bool *split = NULL;
    for (;;) {
        uint32_t nsplit = 0;
        free(split);
        split = il_malloc((size_t)(n ? n : 1u) * sizeof *split, err);
        if (!split) {
            st = IL_ERR_MEMORY;
            break;
        }
        for (uint32_t i = 0; i < n; i++)
            nsplit += (split[i] = il_hr_children_get(elems[i]) != NULL);
        if (nsplit == 0)
            break;
        size_t m = (size_t)n + 3u * nsplit;
        const il_hr_elem **next = il_malloc(m * sizeof *next, err);
        il_patch_mesh *fine = NULL;
        if (!next || (st = il_patch_mesh_refine(s->scene, cur, split, &fine, err)) != IL_OK) {
            free(next);
            st = next ? st : IL_ERR_MEMORY;
            break;
        }
        size_t j = 0;
        for (uint32_t i = 0; i < n; i++) {
            if (!split[i]) {
                next[j++] = elems[i];
                continue;
            }
            const il_hr_elem *kids = il_hr_children_get(elems[i]);
            for (uint32_t k = 0; k < 4; k++)
                next[j++] = &kids[k];
        }
        if (cur != s->mesh)
            il_patch_mesh_release((il_patch_mesh *)cur);
        cur = fine;
        free(elems);
        elems = next;
        n = (uint32_t)m;
        if (fine->num_patches != m) {
            st = il_fail(err, IL_ERR_RUNTIME,
                         "hr: the refined mesh has %u patches where the quadtrees have %zu leaves",
                         fine->num_patches, m);
            break;
        }
    }
    il_vec3 *rad = NULL;
    if (st == IL_OK && !(rad = il_malloc((size_t)(n ? n : 1u) * sizeof *rad, err)))
        st = IL_ERR_MEMORY;
    if (st == IL_OK)
        for (uint32_t i = 0; i < n; i++)
            rad[i] = il_hr_exposed_radiance(elems[i]);
    free(split);
    free(elems);
    if (st != IL_OK) {
        if (cur != s->mesh)
            il_patch_mesh_release((il_patch_mesh *)cur);
        free(rad);
        return st;
    }
    *mesh_out = (il_patch_mesh *)cur; /* s->mesh itself when nothing was split */
    *patch_radiance_out = rad;
    return IL_OK;
}
