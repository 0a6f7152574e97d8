/* Skies for daylight studies as lat-long maps (docs/environment.md#skies).
 *
 * il_sky_overcast: the CIE standard overcast sky (Moon & Spencer 1942,
 * CIE 1955; CIE S 011/E:2003 keeps it as a separate formula): the
 * luminance at altitude a is L(a) = Lz (1 + 2 sin a) / 3, the same in every
 * azimuth.  On an unobstructed horizontal surface it gives E = integral
 * over the sky of L(a) sin a dw = 2 pi Lz / 3 (1/2 + 2/3) = 7 pi Lz / 9,
 * so Lz = 9 E / (7 pi).
 *
 * il_sky_cie: the CIE standard general sky (CIE S 011/E:2003; Kittler,
 * Perez & Darula 1998), relative to the zenith
 *   L(Z, chi) / Lz = f(chi) phi(Z) / (f(Zs) phi(0)),
 *   gradation  phi(Z) = 1 + a exp(b / cos Z)   (phi = 1 at the horizon),
 *   indicatrix f(chi) = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi,
 * Z the zenith angle of the sky element, Zs the sun's, chi the angle between
 * the element and the sun.  The fifteen types combine six gradation groups
 * (a, b) with six indicatrix groups (c, d, e).  The absolute scale comes
 * from the horizontal illuminance asked for.
 *
 * Below the horizon both have a Lambertian ground of albedo rho lit by the
 * sky and the sun: L = rho E / pi, as in Radiance's gensky with its ground
 * glow. */
#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "core/color.h"
#include "core/error.h"
#include "core/vec.h"
#include "image/sky.h"

/* The six gradation groups (a, b) and six indicatrix groups (c, d, e) of
 * CIE S 011/E:2003, Table 1, and the groups each of the fifteen types
 * takes (Table 2). */
static const double gradation[6][2] = {
    {4.0, -0.70}, {1.1, -0.8}, {0.0, -1.0}, {-1.0, -0.55}, {-1.0, -0.32}, {-1.0, -0.15}};
static const double indicatrix[6][3] = {
    {0.0, -1.0, 0.0}, {2.0, -1.5, 0.15}, {5.0, -2.5, 0.30},
    {10.0, -3.0, 0.45}, {16.0, -3.0, 0.30}, {24.0, -2.8, 0.15}};
static const unsigned char type_groups[15][2] = {
    {1, 1}, {1, 2}, {2, 1}, {2, 2}, {3, 1}, {3, 2}, {3, 3}, {3, 4},
    {4, 2}, {4, 3}, {4, 4}, {5, 4}, {5, 5}, {6, 5}, {6, 6}};

il_sky_desc il_sky_with_defaults(const il_sky_desc *desc)
{
    il_sky_desc d = desc ? *desc : (il_sky_desc){0};
    if (d.horizontal_lux == 0.0)
        d.horizontal_lux = 10000.0;
    if (d.ground_albedo == 0.0)
        d.ground_albedo = 0.2;
    if (d.width == 0)
        d.width = 256u;
    if (d.sun_diameter == 0.0)
        d.sun_diameter = IL_SUN_DIAMETER;
    return d;
}

/* The checks and defaults both skies share; `multiple` is what the width
 * must be a multiple of. */
static il_status sky_settings(const il_sky_desc *desc, il_image *out, uint32_t multiple,
                              double *lux, double *albedo, uint32_t *width, il_error *err)
{
    il_sky_desc d = il_sky_with_defaults(desc);
    *lux = d.horizontal_lux;
    *albedo = d.ground_albedo;
    *width = d.width;
    if (!out)
        return il_fail(err, IL_ERR_INVALID, "sky: no output image");
    if (!(*lux > 0.0) || !isfinite(*lux))
        return il_fail(err, IL_ERR_INVALID, "sky: the horizontal illuminance must be a positive number of lux");
    if (!(*albedo <= 1.0))
        return il_fail(err, IL_ERR_INVALID, "sky: the ground albedo must be at most 1");
    if (*albedo < 0.0)
        *albedo = 0.0;
    if (*width < 2 * multiple || *width > 16384 || *width % multiple)
        return il_fail(err, IL_ERR_INVALID, "sky: width %u is not a multiple of %u from %u to 16384",
                       *width, multiple, 2 * multiple);
    return IL_OK;
}

/* Fills the rows whose centre is not above the horizon with the ground's
 * radiance. */
static void fill_ground(il_image *img, float radiance)
{
    for (uint32_t j = img->height / 2; j < img->height; j++)
        for (size_t k = 3 * (size_t)j * img->width; k < 3 * (size_t)(j + 1) * img->width; k++)
            img->rgb[k] = radiance;
}

il_status il_sky_overcast(const il_sky_desc *desc, il_image *out, il_error *err)
{
    double lux, albedo;
    uint32_t width;
    il_status st = sky_settings(desc, out, 2, &lux, &albedo, &width, err);
    if (st != IL_OK)
        return st;
    if (desc && desc->sun_normal_lux != 0.0)
        return il_fail(err, IL_ERR_INVALID, "sky: the overcast sky has no sun");
    uint32_t height = width / 2;
    st = il_image_alloc(out, width, height, err);
    if (st != IL_OK)
        return st;
    double e = lux / IL_LUMENS_PER_WATT;              /* W/m^2 of white light */
    double zenith = 9.0 * e / (7.0 * IL_PI);
    for (uint32_t j = 0; j < height / 2; j++) {
        /* Row j's centre is theta = pi (j + 1/2) / height from +y, at
         * altitude pi/2 - theta (docs/environment.md, lat-long). */
        double altitude = 0.5 * IL_PI - IL_PI * (j + 0.5) / height;
        float l = (float)(zenith * (1.0 + 2.0 * sin(altitude)) / 3.0);
        for (uint32_t i = 0; i < width; i++)
            for (int c = 0; c < 3; c++)
                out->rgb[3 * ((size_t)j * width + i) + c] = l;
    }
    fill_ground(out, (float)(albedo * e / IL_PI));
    return IL_OK;
}

/* The unit vector towards (altitude, azimuth) in degrees, azimuth clockwise
 * from north seen from above; north is -z and east +x, both turned by
 * `north` degrees counter-clockwise about +y (illum.h, il_sky_desc). */
il_vec3 il_sky_direction(double altitude, double azimuth, double north)
{
    double deg = IL_PI / 180.0;
    double h = altitude * deg, a = azimuth * deg, r = north * deg;
    /* Unturned, azimuth a points along cos a (0,0,-1) + sin a (1,0,0);
     * turning by r about +y takes the angle a to a - r. */
    double ca = cos(a - r), sa = sin(a - r);
    return (il_vec3){(float)(cos(h) * sa), (float)sin(h), (float)(-cos(h) * ca)};
}

bool il_sky_type_from_name(const char *name, int *type)
{
    if (!strcmp(name, "overcast") || !strcmp(name, "clear")) {
        *type = !strcmp(name, "clear") ? 12 : 0;
        return true;
    }
    if (strncmp(name, "cie:", 4) || !isdigit((unsigned char)name[4]))
        return false;
    char *end = NULL;
    long n = strtol(name + 4, &end, 10);
    if (*end || n < 1 || n > 15)
        return false;
    *type = (int)n;
    return true;
}

static double cie_gradation(const double g[2], double cos_z)
{
    return cos_z > 0.0 ? 1.0 + g[0] * exp(g[1] / cos_z) : 1.0;
}

static double cie_indicatrix(const double f[3], double chi)
{
    double c = cos(chi);
    return 1.0 + f[0] * (exp(f[1] * chi) - exp(f[1] * 0.5 * IL_PI)) + f[2] * c * c;
}

/* Supersampling of a texel: S x S points, each weighted by its sin(theta). */
#define CIE_SUBSAMPLES 4

il_status il_sky_cie(const il_sky_desc *desc, il_image *out, il_error *err)
{
    double lux, albedo;
    uint32_t width;
    if (!desc)
        return il_fail(err, IL_ERR_INVALID, "sky: the CIE general sky needs a description (its type and the sun)");
    il_status st = sky_settings(desc, out, 4, &lux, &albedo, &width, err);
    if (st != IL_OK)
        return st;
    if (desc->cie_type < 1 || desc->cie_type > 15)
        return il_fail(err, IL_ERR_INVALID, "sky: CIE sky type %d is not 1 to 15", desc->cie_type);
    if (!(desc->sun_altitude > 0.0 && desc->sun_altitude <= 90.0))
        return il_fail(err, IL_ERR_INVALID, "sky: the sun's altitude %g is not above the horizon (0 to 90 degrees)",
                       desc->sun_altitude);
    if (!isfinite(desc->sun_azimuth) || !isfinite(desc->north) || fabs(desc->sun_azimuth) > 1e6 ||
        fabs(desc->north) > 1e6)
        return il_fail(err, IL_ERR_INVALID, "sky: the sun's azimuth and north must be finite numbers of degrees "
                       "within +-1e6");
    if (!(desc->sun_normal_lux >= 0.0) || !isfinite(desc->sun_normal_lux))
        return il_fail(err, IL_ERR_INVALID, "sky: the sun's illuminance must be 0 or a positive number of lux");
    if (!(desc->sun_diameter <= 90.0) || !isfinite(desc->sun_diameter))
        return il_fail(err, IL_ERR_INVALID, "sky: the sun's diameter must be at most 90 degrees (negative: a point)");
    uint32_t height = width / 2;
    st = il_image_alloc(out, width, height, err);
    if (st != IL_OK)
        return st;
    const double *g = gradation[type_groups[desc->cie_type - 1][0] - 1];
    const double *f = indicatrix[type_groups[desc->cie_type - 1][1] - 1];
    il_vec3 s = il_sky_direction(desc->sun_altitude, desc->sun_azimuth, desc->north);
    double zs = 0.5 * IL_PI - desc->sun_altitude * IL_PI / 180.0;
    double zenith = cie_indicatrix(f, zs) * cie_gradation(g, 1.0);
    double horizontal = 0.0; /* of the relative map, W/m^2 per unit of Lz */
    for (uint32_t j = 0; j < height / 2; j++) {
        double t0 = IL_PI * j / height, t1 = IL_PI * (j + 1) / height;
        for (uint32_t i = 0; i < width; i++) {
            double sum = 0.0, weight = 0.0;
            for (int q = 0; q < CIE_SUBSAMPLES; q++) {
                double theta = t0 + (t1 - t0) * (q + 0.5) / CIE_SUBSAMPLES;
                double st_ = sin(theta), ct = cos(theta);
                for (int p = 0; p < CIE_SUBSAMPLES; p++) {
                    double phi = 2.0 * IL_PI * ((i + (p + 0.5) / CIE_SUBSAMPLES) / width - 0.5);
                    double cos_chi = st_ * sin(phi) * s.x + ct * s.y - st_ * cos(phi) * s.z;
                    double chi = acos(fmin(1.0, fmax(-1.0, cos_chi)));
                    sum += st_ * cie_indicatrix(f, chi) * cie_gradation(g, ct);
                    weight += st_;
                }
            }
            double l = sum / (weight * zenith);
            out->rgb[3 * ((size_t)j * width + i)] = (float)l;
            /* A texel is constant radiance over its solid angle; on an
             * upward surface it gives l (2 pi / W) (sin^2 t1 - sin^2 t0) / 2. */
            horizontal += l * (IL_PI / width) * (sin(t1) * sin(t1) - sin(t0) * sin(t0));
        }
    }
    double e_sky = lux / IL_LUMENS_PER_WATT;
    double scale = e_sky / horizontal;
    for (size_t k = 0; k < (size_t)width * (height / 2); k++) {
        float l = (float)(out->rgb[3 * k] * scale);
        out->rgb[3 * k] = out->rgb[3 * k + 1] = out->rgb[3 * k + 2] = l;
    }
    double e_sun = desc->sun_normal_lux / IL_LUMENS_PER_WATT * sin(desc->sun_altitude * IL_PI / 180.0);
    fill_ground(out, (float)(albedo * (e_sky + e_sun) / IL_PI));
    return IL_OK;
}
