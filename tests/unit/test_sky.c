/* il_sky_overcast: the CIE standard overcast sky map.  Its luminance is
 * Lz (1 + 2 sin a) / 3 at altitude a (three times brighter at the zenith
 * than at the horizon), the same in every azimuth; summed over the map's
 * texels as a piecewise-constant sky, an unobstructed horizontal surface
 * receives the requested illuminance (683 lm/W); the ground below the
 * horizon is albedo E / pi.  Bad descriptions are refused. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "illum/illum.h"

#define PI_D 3.14159265358979323846

/* Irradiance on an upward surface from the map's upper rows: each texel a
 * constant radiance over its solid angle (2 pi / W)(cos t0 - cos t1),
 * weighted by its mean cosine (cos^2 t0 - cos^2 t1) / (2 (cos t0 - cos t1)). */
static double horizontal_irradiance(const il_image *img)
{
    double e = 0.0;
    for (uint32_t j = 0; j < img->height / 2; j++) {
        double c0 = cos(PI_D * j / img->height), c1 = cos(PI_D * (j + 1) / img->height);
        for (uint32_t i = 0; i < img->width; i++)
            e += img->rgb[3 * ((size_t)j * img->width + i) + 1] * (2.0 * PI_D / img->width) *
                 (c0 * c0 - c1 * c1) / 2.0;
    }
    return e;
}

int main(void)
{
    il_error err = {0};
    il_image img = {0};
    CHECK_OK(il_sky_overcast(NULL, &img, &err), &err); /* all defaults */
    CHECK(img.width == 256 && img.height == 128);
    double e = horizontal_irradiance(&img);
    printf("defaults: horizontal %.6g W/m^2 = %.6g lx (expected 10000)\n", e, 683.0 * e);
    CHECK_REL(683.0 * e, 10000.0, 2e-3);
    /* Every sky row against the formula at its centre's altitude, relative to
     * the top row; zenith over horizon is (1 + 2) / (1 + 0) = 3 in the limit
     * (2.93 between the rows next to them, half a row from each). */
    double top = img.rgb[1];
    double a0 = PI_D / 2.0 - PI_D * 0.5 / img.height;
    for (uint32_t j = 0; j < img.height / 2; j++) {
        double a = PI_D / 2.0 - PI_D * (j + 0.5) / img.height;
        CHECK_REL(img.rgb[3 * (size_t)j * img.width + 1] / top, (1.0 + 2.0 * sin(a)) / (1.0 + 2.0 * sin(a0)), 1e-5);
    }
    double horizon = img.rgb[3 * (size_t)(img.height / 2 - 1) * img.width + 1];
    CHECK_REL(top / horizon, 3.0, 0.03);
    /* Ground: 0.2 E / pi, in every channel, every texel below the horizon. */
    double ground = 0.2 * 10000.0 / 683.0 / PI_D;
    bool flat = true;
    for (size_t k = 3 * (size_t)(img.height / 2) * img.width; k < 3 * (size_t)img.height * img.width; k++)
        flat = flat && fabs(img.rgb[k] - ground) <= 1e-6 * ground;
    CHECK(flat);
    il_image_free(&img);

    il_sky_desc d = {.horizontal_lux = 25000.0, .ground_albedo = -1.0, .width = 64};
    CHECK_OK(il_sky_overcast(&d, &img, &err), &err);
    CHECK(img.width == 64 && img.height == 32);
    e = horizontal_irradiance(&img);
    printf("64 wide, 25000 lx: %.6g lx\n", 683.0 * e);
    CHECK_REL(683.0 * e, 25000.0, 1e-2);
    CHECK(img.rgb[3 * (size_t)(img.height - 1) * img.width] == 0.0f); /* no ground */
    il_image_free(&img);

    const il_sky_desc bad[] = {{.horizontal_lux = -1.0}, {.horizontal_lux = NAN},
                               {.ground_albedo = 1.5}, {.width = 1001}, {.width = 2}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memset(&err, 0, sizeof err);
        CHECK(il_sky_overcast(&bad[k], &img, &err) == IL_ERR_INVALID);
        printf("bad %zu: %s\n", k, err.message);
    }
    CHECK(il_sky_overcast(NULL, NULL, &err) == IL_ERR_INVALID);
    return check_report();
}
