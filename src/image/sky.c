/* il_sky_overcast: the CIE standard overcast sky as a lat-long map.
 *
 * Moon & Spencer (1942), adopted by the CIE (1955; CIE S 011/E:2003, sky
 * type 1): the luminance at altitude a is L(a) = Lz (1 + 2 sin a) / 3, the
 * same in every azimuth.  On an unobstructed horizontal surface it gives
 * E = integral over the sky of L(a) sin a dw = 2 pi Lz / 3 (1/2 + 2/3) =
 * 7 pi Lz / 9, so Lz = 9 E / (7 pi).  The ground below the horizon is a
 * Lambertian plane of albedo rho lit by that E: L = rho E / pi, as in
 * Radiance's gensky with its ground glow. */
#include <math.h>

#include "core/color.h"
#include "core/error.h"
#include "core/vec.h"

il_status il_sky_overcast(const il_sky_desc *desc, il_image *out, il_error *err)
{
    double lux = desc && desc->horizontal_lux != 0.0 ? desc->horizontal_lux : 10000.0;
    double albedo = desc && desc->ground_albedo != 0.0 ? desc->ground_albedo : 0.2;
    uint32_t width = desc && desc->width ? desc->width : 256u;
    if (!out)
        return il_fail(err, IL_ERR_INVALID, "sky: no output image");
    if (!(lux > 0.0) || !isfinite(lux))
        return il_fail(err, IL_ERR_INVALID, "sky: the horizontal illuminance must be a positive number of lux");
    if (!(albedo <= 1.0))
        return il_fail(err, IL_ERR_INVALID, "sky: the ground albedo must be at most 1");
    if (albedo < 0.0)
        albedo = 0.0;
    if (width < 4 || width > 16384 || width % 2)
        return il_fail(err, IL_ERR_INVALID, "sky: width %u is not an even number from 4 to 16384", width);
    uint32_t height = width / 2;
    il_status st = il_image_alloc(out, width, height, err);
    if (st != IL_OK)
        return st;
    double e = lux / IL_LUMENS_PER_WATT;              /* W/m^2 of white light */
    double zenith = 9.0 * e / (7.0 * IL_PI);
    float ground = (float)(albedo * e / IL_PI);
    for (uint32_t j = 0; j < height; j++) {
        /* Row j's centre is theta = pi (j + 1/2) / height from +y, at
         * altitude pi/2 - theta (docs/environment.md, lat-long). */
        double altitude = 0.5 * IL_PI - IL_PI * (j + 0.5) / height;
        float l = altitude > 0.0 ? (float)(zenith * (1.0 + 2.0 * sin(altitude)) / 3.0) : ground;
        for (uint32_t i = 0; i < width; i++)
            for (int c = 0; c < 3; c++)
                out->rgb[3 * ((size_t)j * width + i) + c] = l;
    }
    return IL_OK;
}
