/* Packs a committed scene into the flat arrays of kernel/kernel_path.h: the
 * BVH, the materials, the vertex normals, the emissive triangles with their
 * power CDF (photon kernels), the path kernel's light table and the camera.
 * CPU only; src/cuda/ copies the arrays to the GPU as they are. */
#ifndef IL_KERNEL_SCENE_H
#define IL_KERNEL_SCENE_H

#include "illum/illum.h"
#include "kernel/bvh_build.h"
#include "kernel/kernel_path.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct il_kscene {
    il_kbvh bvh;
    ilk_material *materials;  uint32_t num_materials;
    uint32_t *lights;         uint32_t num_lights;
    float *light_cdf;         /* num_lights + 1 */
    ilk_light *pt_lights;     uint32_t num_pt_lights;
    float *pt_light_cdf;      /* num_pt_lights + 1 */
    ilk_tri_normals *normals; uint32_t num_normals;  /* bvh.num_tris, or 0 when no mesh has normals */
    ilk_tri_uvs *uvs;         uint32_t num_uvs;      /* bvh.num_tris, or 0 when no material has a texture */
    ilk_texture *textures;    uint32_t num_textures;
    float *texels;            uint64_t num_texels;
    float *env_texels;        uint32_t env_width, env_height; /* NULL without an environment map */
    float *env_cdf;           uint64_t num_env_cdf;           /* its sampling table (ilk_scene.env_cdf) */
    uint32_t env_grid_w, env_grid_h;
    float env_light_pmf;      /* the environment's probability in pt_light_cdf (0: none) */
    float *tri_light_pmf;     /* per triangle, its probability there (NULL: none emits) */
    ilk_scene view;           /* host pointers into the arrays above */
} il_kscene;

/* IL_ERR_INVALID when the scene needs what the photon kernels do not do
 * yet (non-diffuse materials, textures, point/spot/directional lights, an
 * environment): the caller falls back to, or points the user at, the CPU. */
il_status il_kscene_build(const il_scene *scene, uint32_t width, uint32_t height, uint32_t max_depth,
                          uint64_t seed, il_kscene *out, il_error *err);
/* il_kscene_build for the path kernel alone (kernel_path.h), which also
 * renders Phong, mirror and dielectric materials, diffuse textures, point,
 * spot and directional lights and an environment, uniform or a map.  The photon kernels must not take its result (they
 * know only diffuse surfaces and emissive triangles). */
il_status il_kscene_build_pt(const il_scene *scene, uint32_t width, uint32_t height, uint32_t max_depth,
                             uint64_t seed, il_kscene *out, il_error *err);
void il_kscene_free(il_kscene *ks);

#ifdef __cplusplus
}
#endif

#endif
