/* Direct light from point, spot and directional lights and the sky on a
 * patch (shared by the diffuse methods; see patch_direct.c). */
#ifndef IL_METHODS_PATCH_DIRECT_H
#define IL_METHODS_PATCH_DIRECT_H

#include <stdbool.h>
#include <stdint.h>
#include "core/vec.h"
#include "scene/scene.h"

/* Whether the scene has delta lights (point/spot/directional) and a sky
 * that is not black. */
void il_patch_direct_kinds(const il_scene *scene, bool *delta, bool *sky);

/* The mean irradiance over the planar polygon `corners` (3 or 4,
 * counter-clockwise from the front, unit normal n) from the delta lights
 * (when `delta`) and the sky (when `sky`), with shadow rays through the
 * scene's tracer.  Deterministic in (seed, stream). */
il_vec3 il_patch_direct_irradiance(const il_scene *scene, const il_vec3 *corners,
                                   uint32_t num_corners, il_vec3 n, uint64_t seed,
                                   uint64_t stream, bool delta, bool sky);

#endif
