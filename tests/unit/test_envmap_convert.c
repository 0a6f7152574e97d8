/* il_envmap_convert (src/image/envmap_convert.c): the three mappings
 * converted into each other and back.
 *
 * Geometry: a smooth sky given by a formula, sampled into a lat-long map
 * and converted lat-long -> angular -> cross -> lat-long (and the other
 * ways), must still give the formula's radiance in every direction to
 * within the blur of resampling (0.5%, 1% on a cross, whose faces clamp at
 * their edges); a flipped or turned axis anywhere would be off by tens of
 * per cent.
 *
 * The shared maps: lat-long -> angular -> lat-long and lat-long -> cross ->
 * lat-long round trips, angular <-> cross directly, sizes chosen by "width
 * 0", and the light each map holds (its texels' mean radiance over the
 * sphere) kept to 1%.
 *
 * The tolerance of a round trip of a real map.  Each conversion averages
 * the input's bilinear lookups over an output texel's footprint: a blur of
 * about a texel, which spreads the maps' one-texel highlights (Grace's
 * windows, the sun) into their neighbours.  The error measure is the
 * solid-angle-weighted relative L1 difference of luminance,
 * sum |L' - L| dOmega / sum L dOmega, which such highlights dominate; so
 * the bound is relative to the same blur without any change of mapping:
 * a round trip may differ from the original by at most twice as much as
 * two lat-long -> lat-long resamplings do.  The map shifted by two texels
 * (2.8 degrees) or mirrored left to right is checked to exceed that bound,
 * so an error of orientation or position cannot pass. */
#include <string.h>

#include "check.h"
#include "core/vec.h"
#include "image/envmap.h"

#define PI_D 3.14159265358979323846

/* Mean luminance over the sphere of the texels as stored: each texel's
 * luminance times its solid angle (the mapping's Jacobian integrated over
 * the texel by 8 x 8 midpoints; only the part inside the angular map's
 * disk), over 4 pi. */
static double mean_lum(const il_image *img, il_env_mapping m)
{
    double s = 0.0;
    for (uint32_t y = 0; y < img->height; y++)
        for (uint32_t x = 0; x < img->width; x++) {
            double omega = 0.0;
            for (int b = 0; b < 8; b++)
                for (int a = 0; a < 8; a++)
                    omega += il_envmap_jacobian(m, v2((x + (a + 0.5f) / 8) / img->width,
                                                      (y + (b + 0.5f) / 8) / img->height));
            omega /= 64.0 * img->width * img->height;
            const float *p = img->rgb + 3 * ((size_t)y * img->width + x);
            s += il_luminance(v3(p[0], p[1], p[2])) * omega;
        }
    return s / (4.0 * PI_D);
}

/* sum |lum(a) - lum(b)| sin(theta) / sum lum(b) sin(theta) over the texels
 * of two lat-long maps of the same size. */
static double rel_l1(const il_image *a, const il_image *b)
{
    double num = 0.0, den = 0.0;
    for (uint32_t y = 0; y < b->height; y++) {
        double st = sin(PI_D * (y + 0.5) / b->height);
        for (uint32_t x = 0; x < b->width; x++) {
            const float *p = a->rgb + 3 * ((size_t)y * a->width + x);
            const float *q = b->rgb + 3 * ((size_t)y * b->width + x);
            double la = il_luminance(v3(p[0], p[1], p[2])), lb = il_luminance(v3(q[0], q[1], q[2]));
            num += fabs(la - lb) * st;
            den += lb * st;
        }
    }
    return num / den;
}

/* The map shifted by dx texels (wrapping) or mirrored left to right. */
static il_image altered(const il_image *src, int dx, bool mirror)
{
    il_image out = {0};
    il_error err;
    CHECK_OK(il_image_alloc(&out, src->width, src->height, &err), &err);
    int w = (int)src->width;
    for (uint32_t y = 0; y < src->height; y++)
        for (int x = 0; x < w; x++) {
            int sx = mirror ? w - 1 - x : ((x + dx) % w + w) % w;
            memcpy(out.rgb + 3 * ((size_t)y * w + x), src->rgb + 3 * ((size_t)y * w + sx), 3 * sizeof(float));
        }
    return out;
}

/* A smooth sky (positive everywhere). */
static double sky(il_vec3 d)
{
    return 1.0 + 0.5 * d.x + 0.3 * d.y * d.y + 0.4 * d.z * d.x + 0.2 * d.z;
}

/* Worst relative error of a map's lookups against sky() over the sphere. */
static double sky_error(const il_image *img, il_env_mapping m)
{
    const int n = 20000;
    double worst = 0.0;
    for (int i = 0; i < n; i++) {
        double z = 1.0 - (2.0 * i + 1.0) / n, r = sqrt(fmax(0.0, 1.0 - z * z));
        double phi = i * PI_D * (3.0 - sqrt(5.0));
        il_vec3 d = v3((float)(r * cos(phi)), (float)z, (float)(r * sin(phi)));
        double e = fabs(il_envmap_lookup(img, m, d).x - sky(d)) / sky(d);
        worst = fmax(worst, e);
    }
    return worst;
}

static void smooth_sky(void)
{
    il_error err;
    il_image ll = {0};
    CHECK_OK(il_image_alloc(&ll, 256, 128, &err), &err);
    for (uint32_t y = 0; y < ll.height; y++)
        for (uint32_t x = 0; x < ll.width; x++) {
            il_vec3 d;
            il_envmap_uv_to_dir(IL_ENV_LATLONG, v2((x + 0.5f) / ll.width, (y + 0.5f) / ll.height), &d);
            float *p = ll.rgb + 3 * ((size_t)y * ll.width + x);
            p[0] = p[1] = p[2] = (float)sky(d);
        }
    il_image ang = {0}, cross = {0}, ll2 = {0}, cross2 = {0}, ang2 = {0};
    CHECK_OK(il_envmap_convert(&ll, IL_ENV_LATLONG, IL_ENV_ANGULAR, 0, &ang, &err), &err);
    CHECK_OK(il_envmap_convert(&ang, IL_ENV_ANGULAR, IL_ENV_CROSS, 0, &cross, &err), &err);
    CHECK_OK(il_envmap_convert(&cross, IL_ENV_CROSS, IL_ENV_LATLONG, 0, &ll2, &err), &err);
    CHECK_OK(il_envmap_convert(&ll, IL_ENV_LATLONG, IL_ENV_CROSS, 0, &cross2, &err), &err);
    CHECK_OK(il_envmap_convert(&cross2, IL_ENV_CROSS, IL_ENV_ANGULAR, 0, &ang2, &err), &err);
    if (ll2.rgb && ang2.rgb) {
        double e0 = sky_error(&ll, IL_ENV_LATLONG), e1 = sky_error(&ang, IL_ENV_ANGULAR);
        double e2 = sky_error(&cross, IL_ENV_CROSS), e3 = sky_error(&ll2, IL_ENV_LATLONG);
        double e4 = sky_error(&cross2, IL_ENV_CROSS), e5 = sky_error(&ang2, IL_ENV_ANGULAR);
        printf("smooth sky, worst error of the lookups: lat-long %.2g, ->angular %.2g, ->cross %.2g, "
               "->lat-long %.2g; lat-long->cross %.2g, ->angular %.2g\n", e0, e1, e2, e3, e4, e5);
        /* The cross filters within a face and clamps at its edges: within
         * half a texel of an edge a lookup returns the edge texel, off by
         * half a texel (~0.012 rad here) times the gradient (< 1): up to
         * 1% there; elsewhere bilinear error and blur, O(texel^2). */
        CHECK(e0 < 0.005 && e1 < 0.005 && e3 < 0.005 && e5 < 0.005);
        CHECK(e2 < 0.01 && e4 < 0.01);
    }
    il_image_free(&ll);
    il_image_free(&ang);
    il_image_free(&cross);
    il_image_free(&ll2);
    il_image_free(&cross2);
    il_image_free(&ang2);
}

static void round_trip(const char *file, bool direct)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/scenes/envmaps/%s", IL_SHARED_DIR, file);
    il_error err;
    il_image ll = {0};
    il_status st = il_image_read(path, &ll, &err);
    CHECK_OK(st, &err);
    if (st != IL_OK)
        return;
    double m0 = mean_lum(&ll, IL_ENV_LATLONG);

    il_image ang = {0}, cross = {0}, back_a = {0}, back_c = {0}, cross_from_ang = {0}, ang_from_cross = {0};
    CHECK_OK(il_envmap_convert(&ll, IL_ENV_LATLONG, IL_ENV_ANGULAR, 0, &ang, &err), &err);
    CHECK_OK(il_envmap_convert(&ll, IL_ENV_LATLONG, IL_ENV_CROSS, 0, &cross, &err), &err);
    /* "Width 0": the same texel angle, pi / height at the lat-long map's
     * equator, 2 pi / width at the angular map's centre, pi / 2 per face
     * width on the cross. */
    CHECK(ang.width == 2 * ll.height && ang.height == ang.width);
    CHECK(cross.width == 3 * (ll.height / 2) && cross.height == 4 * (ll.height / 2));
    CHECK_OK(il_envmap_convert(&ang, IL_ENV_ANGULAR, IL_ENV_LATLONG, 0, &back_a, &err), &err);
    CHECK_OK(il_envmap_convert(&cross, IL_ENV_CROSS, IL_ENV_LATLONG, 0, &back_c, &err), &err);
    CHECK(back_a.width == ll.width && back_a.height == ll.height);
    CHECK(back_c.width == ll.width && back_c.height == ll.height);
    /* Angular <-> cross directly (the 1k map: skipped, for time). */
    const il_image *cfa = &cross, *afc = &ang;
    if (direct) {
        CHECK_OK(il_envmap_convert(&ang, IL_ENV_ANGULAR, IL_ENV_CROSS, 0, &cross_from_ang, &err), &err);
        CHECK_OK(il_envmap_convert(&cross, IL_ENV_CROSS, IL_ENV_ANGULAR, 0, &ang_from_cross, &err), &err);
        cfa = &cross_from_ang;
        afc = &ang_from_cross;
    }
    if (!back_a.rgb || !back_c.rgb || !cfa->rgb || !afc->rgb)
        return;

    double ma = mean_lum(&ang, IL_ENV_ANGULAR), mc = mean_lum(&cross, IL_ENV_CROSS);
    double mba = mean_lum(&back_a, IL_ENV_LATLONG), mbc = mean_lum(&back_c, IL_ENV_LATLONG);
    double mca = mean_lum(cfa, IL_ENV_CROSS), mac = mean_lum(afc, IL_ENV_ANGULAR);
    printf("%s: mean luminance lat-long %.5g, angular %+.3f%%, cross %+.3f%%, back from angular %+.3f%%, "
           "back from cross %+.3f%%, angular->cross %+.3f%%, cross->angular %+.3f%%\n",
           file, m0, 100 * (ma / m0 - 1), 100 * (mc / m0 - 1), 100 * (mba / m0 - 1), 100 * (mbc / m0 - 1),
           100 * (mca / m0 - 1), 100 * (mac / m0 - 1));
    /* The light is kept: the output texels are solid-angle means. */
    CHECK_REL(ma, m0, 0.01);
    CHECK_REL(mc, m0, 0.01);
    CHECK_REL(mba, m0, 0.01);
    CHECK_REL(mbc, m0, 0.01);
    CHECK_REL(mca, m0, 0.01);
    CHECK_REL(mac, m0, 0.01);

    /* The blur of two resamplings alone: lat-long -> lat-long twice. */
    il_image id1 = {0}, id2 = {0};
    CHECK_OK(il_envmap_convert(&ll, IL_ENV_LATLONG, IL_ENV_LATLONG, 0, &id1, &err), &err);
    CHECK_OK(il_envmap_convert(&id1, IL_ENV_LATLONG, IL_ENV_LATLONG, 0, &id2, &err), &err);
    if (!id2.rgb)
        return;
    double blur = rel_l1(&id2, &ll), bound = 2.0 * blur;
    double ea = rel_l1(&back_a, &ll), ec = rel_l1(&back_c, &ll);
    il_image shifted = altered(&ll, 2, false), mirrored = altered(&ll, 0, true);
    double es = rel_l1(&shifted, &ll), em = rel_l1(&mirrored, &ll);
    printf("%s: error of two lat-long resamplings %.4f; round trip via angular %.4f, via cross %.4f; "
           "the map shifted by 2 texels %.4f, mirrored %.4f (bound %.4f)\n",
           file, blur, ea, ec, es, em, bound);
    CHECK(ea < bound);
    CHECK(ec < bound);
    CHECK(es > bound);
    CHECK(em > bound);
    il_image_free(&id1);
    il_image_free(&id2);
    il_image_free(&shifted);
    il_image_free(&mirrored);
    il_image_free(&ll);
    il_image_free(&ang);
    il_image_free(&cross);
    il_image_free(&back_a);
    il_image_free(&back_c);
    il_image_free(&cross_from_ang);
    il_image_free(&ang_from_cross);
}

static void bad_input(void)
{
    il_error err;
    il_image img = {0}, out = {0};
    CHECK_OK(il_image_alloc(&img, 30, 20, &err), &err);
    CHECK(il_envmap_convert(&img, IL_ENV_ANGULAR, IL_ENV_LATLONG, 0, &out, &err) == IL_ERR_INVALID);
    CHECK(strstr(err.message, "square") != NULL && out.rgb == NULL);
    CHECK(il_envmap_convert(&img, IL_ENV_CROSS, IL_ENV_LATLONG, 0, &out, &err) == IL_ERR_INVALID);
    CHECK(il_envmap_convert(&img, IL_ENV_LATLONG, IL_ENV_CROSS, 100, &out, &err) == IL_ERR_INVALID);
    CHECK(il_envmap_convert(&img, IL_ENV_LATLONG, IL_ENV_LATLONG, 33, &out, &err) == IL_ERR_INVALID);
    CHECK(il_envmap_convert(&img, IL_ENV_LATLONG, IL_ENV_ANGULAR, 1u << 20, &out, &err) == IL_ERR_INVALID);
    CHECK_OK(il_envmap_convert(&img, IL_ENV_LATLONG, IL_ENV_CROSS, 99, &out, &err), &err);
    CHECK(out.width == 99 && out.height == 132);
    il_image_free(&out);
    img.rgb[5] = NAN;
    CHECK(il_envmap_convert(&img, IL_ENV_LATLONG, IL_ENV_CROSS, 0, &out, &err) == IL_ERR_INVALID);
    il_image_free(&img);

    /* A constant map stays constant, whatever the mappings (the angular
     * map's corners outside the disk are black). */
    CHECK_OK(il_image_alloc(&img, 64, 32, &err), &err);
    for (size_t k = 0; k < 3 * 64 * 32; k++)
        img.rgb[k] = 2.5f;
    il_image cr = {0}, an = {0};
    CHECK_OK(il_envmap_convert(&img, IL_ENV_LATLONG, IL_ENV_CROSS, 0, &cr, &err), &err);
    CHECK_OK(il_envmap_convert(&cr, IL_ENV_CROSS, IL_ENV_ANGULAR, 0, &an, &err), &err);
    float lo = 1e9f, hi = -1e9f;
    for (uint32_t y = 0; an.rgb && y < an.height; y++)
        for (uint32_t x = 0; x < an.width; x++) {
            il_vec3 d;
            if (!il_envmap_uv_to_dir(IL_ENV_ANGULAR, v2((x + 0.5f) / an.width, (y + 0.5f) / an.height), &d))
                continue;
            float v = an.rgb[3 * ((size_t)y * an.width + x)];
            lo = il_minf(lo, v);
            hi = il_maxf(hi, v);
        }
    CHECK_NEAR(lo, 2.5, 1e-4);
    CHECK_NEAR(hi, 2.5, 1e-4);
    CHECK(an.rgb && an.rgb[0] == 0.0f);
    il_image_free(&cr);
    il_image_free(&an);
    il_image_free(&img);
}

int main(void)
{
    bad_input();
    smooth_sky();
    round_trip("probulator_grace_256x128.hdr", true);
    round_trip("probulator_uffizi_256x128.hdr", true);
    round_trip("probulator_pisa_256x128.hdr", true);
    round_trip("probulator_ennis_256x128.hdr", true);
    round_trip("probulator_wells_256x128.hdr", true);
    round_trip("polyhaven_pedestrian_overpass_1k.hdr", false);
    return check_report();
}
