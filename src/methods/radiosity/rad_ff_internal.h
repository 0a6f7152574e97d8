/* Internals shared by the form-factor files (rad_ff*.c, rad_hemicube.c). */
#ifndef IL_METHODS_RADIOSITY_RAD_FF_INTERNAL_H
#define IL_METHODS_RADIOSITY_RAD_FF_INTERNAL_H

#include "methods/radiosity/rad.h"

/* Both back-ends tally into `scratch` (one float per patch, zero elsewhere)
 * and list each patch the first time it gets a non-zero tally in
 * row->index[0 .. row->count).  This turns that into the sorted sparse row
 * (values times `scale`) and re-zeroes the touched scratch entries. */
void il_ff_row_compact(float *scratch, uint32_t num_patches, float scale, il_ff_row *row);

/* il_ff_ray_row with a caller's buffer `order` of 2 * samples il_vec2 (or
 * NULL): with it the rays are traced in direction-stratum order, which is
 * faster; the row is the same either way. */
void il_ff_ray_row_ordered(const il_patch_mesh *mesh, uint32_t samples, uint64_t seed, uint32_t i,
                           float *scratch, il_vec2 *order, il_ff_row *out);

#endif
