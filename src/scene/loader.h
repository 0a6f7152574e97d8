/* Scene file loaders; il_scene_load (load.c) picks one by name or extension. */
#ifndef IL_SCENE_LOADER_H
#define IL_SCENE_LOADER_H

#include "illum/illum.h"

/* Any format assimp reads (OBJ+MTL, glTF/GLB, PLY, 3DS, ...), into an existing scene.
 * `transform` is an optional column-major 4x4 matrix applied to positions
 * and normals (NULL: identity); `material_override` (0: none) replaces every
 * material of the file. */
il_status il_load_assimp(il_scene *scene, const char *path, const float *transform,
                         uint32_t material_override, il_error *err);
/* A JSON scene file (docs/scene-format.md). */
il_status il_load_json(il_scene *scene, const char *path, il_error *err);

#endif
