/* Skies for daylight studies (sky.c; the public il_sky_* in illum.h). */
#ifndef IL_IMAGE_SKY_H
#define IL_IMAGE_SKY_H

#include <stdbool.h>

#include "illum/illum.h"

/* The unit vector in the scene towards (altitude, azimuth), degrees, azimuth
 * clockwise from north seen from above, north being -z turned by `north`
 * degrees counter-clockwise about +y (il_sky_desc). */
il_vec3 il_sky_direction(double altitude, double azimuth, double north);

/* "overcast" (0), "clear" (12) or "cie:N" (N from 1 to 15) into *type;
 * false for anything else. */
bool il_sky_type_from_name(const char *name, int *type);

/* The sun's mean apparent diameter in degrees: 32 arc minutes (31.6' in
 * early July to 32.7' in early January, with the earth's distance). */
#define IL_SUN_DIAMETER 0.533

/* desc with the defaults of its zero fields filled in: horizontal_lux
 * 10,000, ground_albedo 0.2, width 256, sun_diameter IL_SUN_DIAMETER (a
 * zero desc when NULL). */
il_sky_desc il_sky_with_defaults(const il_sky_desc *desc);

#endif
