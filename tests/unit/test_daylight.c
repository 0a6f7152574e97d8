/* Daylight: the sun's position (il_sun_position) against NREL's published
 * Solar Position Algorithm example (Reda & Andreas 2004/2008, NREL/TP-560-
 * 34302, Table A4.1/A5.1), the IES direct-normal model (il_sun_normal_lux)
 * against hand-worked values, the CIE overcast sky (il_sky_overcast) and
 * the CIE standard general sky (il_sky_cie) against their formulas, written
 * out here with the standards' numbers: their normalisation, the general
 * sky's orientation, their grounds. */
#include <math.h>
#include <string.h>

#include "check.h"
#include "illum/illum.h"
#include "scene/sun.h"

#define PI_D 3.14159265358979323846
#define DEG (PI_D / 180.0)

static void test_sun_position(void)
{
    il_error err = {0};
    double h = 0.0, a = 0.0;
    /* SPA's example: 2003-10-17 12:30:30 at UTC-7, 39.742476 N, 105.1786 W:
     * topocentric zenith 50.111622 degrees (refracted at 820 hPa, 11 C) and
     * azimuth 194.340241 degrees. */
    CHECK_OK(il_sun_position(39.742476, -105.1786, 1066419030.0, &h, &a, &err), &err);
    printf("SPA example: altitude %.5f (SPA %.5f), azimuth %.5f (SPA 194.34024)\n", h, 90.0 - 50.111622, a);
    CHECK_NEAR(h, 90.0 - 50.111622, 0.02);
    CHECK_NEAR(a, 194.340241, 0.02);
    /* SPA's sun transit that day, 11:46:05 local (18:46:05 UTC): due south. */
    CHECK_OK(il_sun_position(39.742476, -105.1786, 1066416365.0, &h, &a, &err), &err);
    printf("SPA transit: azimuth %.4f (180)\n", a);
    CHECK_NEAR(a, 180.0, 0.1);
    /* At the north pole on the June solstice the sun circles at the
     * obliquity (23.44 degrees) plus refraction (0.04); the south pole is dark. */
    CHECK_OK(il_sun_position(90.0, 0.0, 1782043200.0, &h, &a, &err), &err);
    printf("north pole, 2026-06-21 12:00 UTC: altitude %.4f\n", h);
    CHECK_NEAR(h, 23.44 + 0.04, 0.03);
    CHECK_OK(il_sun_position(-90.0, 0.0, 1782043200.0, &h, &a, &err), &err);
    CHECK(h < -23.0);
    /* Twelve hours after the transit the sun is at its lowest, due north. */
    CHECK_OK(il_sun_position(39.742476, -105.1786, 1066416365.0 + 43200.0, &h, &a, &err), &err);
    CHECK(h < -30.0);
    CHECK(fabs(a - 360.0) < 0.5 || a < 0.5);

    const double bad[][3] = {{91.0, 0.0, 0.0}, {NAN, 0.0, 0.0}, {0.0, 181.0, 0.0}, {0.0, NAN, 0.0},
                             {0.0, 0.0, 4200000000.0}, {0.0, 0.0, -2300000000.0}, {0.0, 0.0, NAN}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memset(&err, 0, sizeof err);
        CHECK(il_sun_position(bad[k][0], bad[k][1], bad[k][2], &h, &a, &err) == IL_ERR_INVALID);
        printf("bad %zu: %s\n", k, err.message);
    }
    CHECK(il_sun_position(0.0, 0.0, 0.0, NULL, &a, &err) == IL_ERR_INVALID);
}

static void test_sun_normal_lux(void)
{
    /* 127,500 x 1.034 x exp(-0.21): type 12, the sun overhead, on 2 January. */
    CHECK_REL(il_sun_normal_lux(12, 90.0, 2), 106863.374, 1e-6);
    /* 127,500 x exp(-0.8 x 2): partly cloudy, 30 degrees up, no season. */
    CHECK_REL(il_sun_normal_lux(8, 30.0, 0), 25741.806, 1e-6);
    /* The seasonal term is smallest in early July: 1 - 0.034 on day 184.5. */
    CHECK(il_sun_normal_lux(15, 45.0, 184) < il_sun_normal_lux(15, 45.0, 0));
    CHECK(il_sun_normal_lux(3, 45.0, 100) == 0.0);   /* overcast types: no sun */
    CHECK(il_sun_normal_lux(0, 45.0, 100) == 0.0);
    CHECK(il_sun_normal_lux(12, 0.0, 100) == 0.0);   /* on the horizon */
    CHECK(il_sun_normal_lux(12, -5.0, 100) == 0.0);
}

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

/* The CIE standard overcast sky map (il_sky_overcast): its luminance is
 * Lz (1 + 2 sin a) / 3 at altitude a (three times brighter at the zenith
 * than at the horizon), the same in every azimuth; summed over the map's
 * texels as a piecewise-constant sky, an unobstructed horizontal surface
 * receives the requested illuminance (683 lm/W); the ground below the
 * horizon is albedo E / pi.  Bad descriptions are refused. */
static void test_overcast_sky(void)
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
}

/* CIE S 011/E:2003's relative luminance for type 12 (gradation group V: a =
 * -1, b = -0.32; indicatrix group 4: c = 10, d = -3, e = 0.45) at zenith
 * angle z, chi from the sun at zenith angle zs. */
static double type12(double z, double chi, double zs)
{
    double phi_z = 1.0 - exp(-0.32 / cos(z)), phi_0 = 1.0 - exp(-0.32);
    double f_chi = 1.0 + 10.0 * (exp(-3.0 * chi) - exp(-1.5 * PI_D)) + 0.45 * cos(chi) * cos(chi);
    double f_zs = 1.0 + 10.0 * (exp(-3.0 * zs) - exp(-1.5 * PI_D)) + 0.45 * cos(zs) * cos(zs);
    return f_chi * phi_z / (f_zs * phi_0);
}

/* The lat-long texel (i, j)'s centre direction (docs/environment.md). */
static void texel_dir(const il_image *img, uint32_t i, uint32_t j, double d[3])
{
    double theta = PI_D * (j + 0.5) / img->height, phi = 2.0 * PI_D * ((i + 0.5) / img->width - 0.5);
    d[0] = sin(theta) * sin(phi);
    d[1] = cos(theta);
    d[2] = -sin(theta) * cos(phi);
}

static void brightest(const il_image *img, uint32_t *bi, uint32_t *bj)
{
    float best = -1.0f;
    for (uint32_t j = 0; j < img->height; j++)
        for (uint32_t i = 0; i < img->width; i++)
            if (img->rgb[3 * ((size_t)j * img->width + i)] > best) {
                best = img->rgb[3 * ((size_t)j * img->width + i)];
                *bi = i;
                *bj = j;
            }
}

static void test_cie_sky(void)
{
    il_error err = {0};
    il_image img = {0};
    /* The clear sky with the sun 40 degrees up in the east (+x). */
    il_sky_desc d = {.cie_type = 12, .sun_altitude = 40.0, .sun_azimuth = 90.0,
                     .sun_normal_lux = 50000.0};
    CHECK_OK(il_sky_cie(&d, &img, &err), &err);
    CHECK(img.width == 256 && img.height == 128);
    double e = 683.0 * horizontal_irradiance(&img);
    printf("type 12: horizontal %.4f lx (10000)\n", e);
    CHECK_REL(e, 10000.0, 1e-5);
    /* Every sky texel against the formula at its centre, relative to a
     * texel 45 degrees up in the west.  A texel holds the mean over its
     * solid angle, which departs from its centre's value near the sun and in
     * the two rows around the zenith (wedges whose centroid is not their
     * centre), so those are left out. */
    double s[3] = {cos(40.0 * DEG), sin(40.0 * DEG), 0.0}, zs = 50.0 * DEG;
    double dr[3];
    uint32_t ri = img.width / 4, rj = img.height / 4;
    texel_dir(&img, ri, rj, dr);
    double ref = img.rgb[3 * ((size_t)rj * img.width + ri) + 1] /
                 type12(acos(dr[1]), acos(dr[0] * s[0] + dr[1] * s[1] + dr[2] * s[2]), zs);
    double worst = 0.0;
    for (uint32_t j = 2; j < img.height / 2; j++)
        for (uint32_t i = 0; i < img.width; i++) {
            double dd[3];
            texel_dir(&img, i, j, dd);
            double chi = acos(fmin(1.0, dd[0] * s[0] + dd[1] * s[1] + dd[2] * s[2]));
            if (chi < 10.0 * DEG)
                continue;
            double want = ref * type12(acos(dd[1]), chi, zs);
            worst = fmax(worst, fabs(img.rgb[3 * ((size_t)j * img.width + i) + 1] / want - 1.0));
        }
    printf("type 12: largest departure from the formula %.2e\n", worst);
    CHECK(worst < 2e-3);
    /* The brightest texel is the sun's: three quarters across (+x), 50
     * degrees down from the zenith. */
    uint32_t bi = 0, bj = 0;
    brightest(&img, &bi, &bj);
    printf("brightest texel (%u, %u); the sun's is (%u, %u)\n", bi, bj, 3 * img.width / 4, 50 * img.height / 180);
    CHECK(abs((int)bi - (int)(3 * img.width / 4)) <= 1 && abs((int)bj - (int)(50 * img.height / 180)) <= 1);
    /* Ground: 0.2 (10,000 + 50,000 sin 40) / (683 pi). */
    double ground = 0.2 * (10000.0 + 50000.0 * sin(40.0 * DEG)) / 683.0 / PI_D;
    CHECK_REL(img.rgb[3 * ((size_t)img.height * img.width - 1)], ground, 1e-6);
    il_image_free(&img);

    /* North turned 90 degrees (north is -x): the east lies along -z, the
     * middle of the map. */
    d.north = 90.0;
    CHECK_OK(il_sky_cie(&d, &img, &err), &err);
    brightest(&img, &bi, &bj);
    CHECK(abs((int)bi - (int)(img.width / 2)) <= 1);
    il_image_free(&img);

    /* Types 1, 3 and 5 (indicatrix group 1) do not depend on the sun's
     * azimuth; type 1 is about three times brighter at the zenith than at
     * the horizon, like the Moon & Spencer sky (1 + 4 e^-0.7 = 2.99). */
    il_image other = {0};
    for (int type = 1; type <= 5; type += 2) {
        il_sky_desc u = {.cie_type = type, .sun_altitude = 30.0, .sun_azimuth = 10.0, .width = 64};
        CHECK_OK(il_sky_cie(&u, &img, &err), &err);
        u.sun_azimuth = 200.0;
        CHECK_OK(il_sky_cie(&u, &other, &err), &err);
        CHECK(memcmp(img.rgb, other.rgb, sizeof(float) * 3 * img.width * img.height) == 0);
        if (type == 1) {
            /* The top and bottom sky rows of this 64 x 32 map have their
             * centres 2.8 degrees from the zenith and the horizon; a texel
             * holds its mean, 0.1% off its centre's value there. */
            double zc = 0.5 * PI_D / img.height, zh = PI_D / 2.0 - zc;
            double zenith_over_horizon = img.rgb[0] / img.rgb[3 * (size_t)(img.height / 2 - 1) * img.width];
            printf("type 1: zenith / horizon row %.4f\n", zenith_over_horizon);
            CHECK_NEAR(zenith_over_horizon, (1.0 + 4.0 * exp(-0.7 / cos(zc))) / (1.0 + 4.0 * exp(-0.7 / cos(zh))), 4e-3);
        }
        il_image_free(&img);
        il_image_free(&other);
    }

    const il_sky_desc bad[] = {{.cie_type = 0, .sun_altitude = 30.0},
                               {.cie_type = 16, .sun_altitude = 30.0},
                               {.cie_type = 12, .sun_altitude = 0.0},
                               {.cie_type = 12, .sun_altitude = -3.0},
                               {.cie_type = 12, .sun_altitude = 91.0},
                               {.cie_type = 12, .sun_altitude = NAN},
                               {.cie_type = 12, .sun_altitude = 30.0, .sun_azimuth = NAN},
                               {.cie_type = 12, .sun_altitude = 30.0, .north = INFINITY},
                               {.cie_type = 12, .sun_altitude = 30.0, .sun_normal_lux = -1.0},
                               {.cie_type = 12, .sun_altitude = 30.0, .width = 6},
                               {.cie_type = 12, .sun_altitude = 30.0, .horizontal_lux = -5.0}};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        memset(&err, 0, sizeof err);
        CHECK(il_sky_cie(&bad[k], &img, &err) == IL_ERR_INVALID);
        printf("bad sky %zu: %s\n", k, err.message);
    }
    CHECK(il_sky_cie(NULL, &img, &err) == IL_ERR_INVALID);
    CHECK(il_sky_overcast(&(il_sky_desc){.sun_normal_lux = 1000.0}, &img, &err) == IL_ERR_INVALID);
    printf("overcast with a sun: %s\n", err.message);
}

/* ISO 8601 moments with their UTC offsets (il_parse_moment, shared by
 * --sun-time and the JSON "sun"). */
static void test_moments(void)
{
    static const struct { const char *text; double seconds; int day; } good[] = {
        {"2003-10-17T12:30:30-07:00", 1066419030.0, 290},
        {"2003-10-17T19:30:30Z", 1066419030.0, 290},
        {"2003-10-17 21:30:30+0200", 1066419030.0, 290},
        {"2003-10-17T19:30:30.25z", 1066419030.25, 290},
        {"2026-06-21T14:30+02", 1782045000.0, 172},
        {"2024-02-29T00:00Z", 1709164800.0, 60},
        {"2024-12-31T23:59:59Z", 1735689599.0, 366},
        {"2026-01-01T00:30+01:00", 1767223800.0, 1},   /* 2025-12-31 23:30 UTC, local New Year's Day */
        {"1900-01-01T00:00Z", -2208988800.0, 1},
    };
    for (size_t k = 0; k < sizeof good / sizeof good[0]; k++) {
        il_error err = {0};
        double t = 0.0;
        int day = 0;
        CHECK_OK(il_parse_moment(good[k].text, &t, &day, &err), &err);
        if (t != good[k].seconds || day != good[k].day)
            printf("%s: %.2f day %d, expected %.2f day %d\n", good[k].text, t, day, good[k].seconds, good[k].day);
        CHECK(t == good[k].seconds && day == good[k].day);
    }
    static const char *const bad[] = {"2026-06-21T12:00", "2026-06-21", "2026-6-21T12:00Z", "2026-06-21T24:00Z",
                                      "2026-06-21T12:60Z", "2026-02-29T12:00Z", "2100-02-29T12:00Z",
                                      "1899-12-31T23:59Z", "2101-01-01T00:00Z", "2026-13-01T00:00Z",
                                      "2026-06-21T12:00+15:00", "2026-06-21T12:00Zx", "2026-06-21T12:00+2",
                                      "tomorrow", ""};
    for (size_t k = 0; k < sizeof bad / sizeof bad[0]; k++) {
        il_error err = {0};
        double t = 0.0;
        int day = 0;
        CHECK(il_parse_moment(bad[k], &t, &day, &err) == IL_ERR_INVALID);
        printf("bad moment '%s': %s\n", bad[k], err.message);
    }
}

int main(void)
{
    test_sun_position();
    test_moments();
    test_sun_normal_lux();
    test_overcast_sky();
    test_cie_sky();
    return check_report();
}
