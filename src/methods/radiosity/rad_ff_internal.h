/* Internals shared by the form-factor files (rad_ff*.c, rad_hemicube.c). */
#ifndef IL_METHODS_RADIOSITY_RAD_FF_INTERNAL_H
#define IL_METHODS_RADIOSITY_RAD_FF_INTERNAL_H

#include "methods/radiosity/rad.h"

/* Both back-ends tally into `scratch` (one float per patch, zero elsewhere)
 * and list each patch the first time it gets a non-zero tally in
 * row->index[0 .. row->count).  This turns that into the sorted sparse row
 * (values times `scale`) and re-zeroes the touched scratch entries. */
void il_ff_row_compact(float *scratch, uint32_t num_patches, float scale, il_ff_row *row);

#endif
