/* Writers behind il_bake_write (export.c): one per file format. */
#ifndef IL_SCENE_EXPORT_H
#define IL_SCENE_EXPORT_H

#include "illum/illum.h"

/* The display colour of a radiance: radiance * 2^exposure per channel, zero
 * when any channel is not finite.  Shared by both writers. */
void il_bake_display_rgb(const float *radiance, float scale, float out[3]);

/* Binary little-endian PLY (export.c). */
il_status il_bake_write_ply(const il_bake_result *bake, const char *path, float exposure,
                            il_error *err);
/* glTF 2.0 through assimp's exporter: binary (.glb) when `binary`, else
 * .gltf with its buffer in a .bin file beside it (export_assimp.c). */
il_status il_bake_write_gltf(const il_bake_result *bake, const char *path, float exposure,
                             bool binary, il_error *err);

#endif
