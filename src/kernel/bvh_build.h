/* The CPU side of the shared ray caster: builds the flattened binary BVH of
 * kernel/kernel_bvh.h over a committed scene's triangles (binned SAH), ready
 * to be traversed on the CPU or copied to a GPU as it is. */
#ifndef IL_KERNEL_BVH_BUILD_H
#define IL_KERNEL_BVH_BUILD_H

#include "illum/illum.h"
#include "kernel/kernel_bvh.h"

typedef struct il_scene il_scene;

#ifdef __cplusplus
extern "C" {
#endif

typedef struct il_kbvh {
    ilk_bvh_node *nodes;   uint32_t num_nodes;
    ilk_tri *tris;         uint32_t num_tris;
    uint32_t depth;        /* levels below the root of the deepest leaf */
    uint32_t num_leaves;
} il_kbvh;

/* Builds over every triangle of every mesh of the scene (positions as given
 * to il_scene_add_mesh; the scene need not be committed).  Zero triangles
 * give an empty BVH that nothing hits.  Free with il_kbvh_free. */
il_status il_kbvh_build_scene(const il_scene *scene, il_kbvh *out, il_error *err);

/* Builds over num_tris indexed triangles (3 indices each into positions);
 * tris[k].prim is the triangle's index, mesh 0, pad pad[prim] (0 when pad
 * is NULL). */
il_status il_kbvh_build_indexed(const il_vec3 *positions, const uint32_t *indices, uint32_t num_tris,
                                const uint32_t *pad, il_kbvh *out, il_error *err);

/* The traversal view of a built BVH (host pointers). */
ilk_bvh il_kbvh_view(const il_kbvh *bvh);

void il_kbvh_free(il_kbvh *bvh);

#ifdef __cplusplus
}
#endif

#endif
