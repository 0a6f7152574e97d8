/* Spectral colour: the CIE tables against their published sums, the XYZ ->
 * Rec.709 matrix against the D65 white point, and the spectrum conversions. */
#include "check.h"
#include "core/color.h"

/* XYZ scaled to Y = 1. */
static il_vec3 v3_div_y(il_vec3 c)
{
    return (il_vec3){c.x / c.y, 1.0f, c.z / c.y};
}

static void test_tables(void)
{
    /* Riemann sums of the 5 nm table times 5 nm: the known integrals of the
     * CIE 1931 functions (106.857 for ybar from the 1 nm table; 106.866 and
     * 106.893 for xbar and zbar at 5 nm). */
    double sx = 0.0, sy = 0.0, sz = 0.0;
    for (int l = 360; l <= 830; l += 5) {
        il_vec3 c = il_cie_cmf(l);
        sx += c.x;
        sy += c.y;
        sz += c.z;
    }
    CHECK_NEAR(sy * 5.0, 106.857, 0.01);
    CHECK_NEAR(sx * 5.0, 106.866, 0.01);
    CHECK_NEAR(sz * 5.0, 106.893, 0.01);
    /* The exact integral of the interpolated ybar is the trapezoid sum: the
     * Riemann sum less half of the (tiny) end values. */
    CHECK_NEAR(il_cie_y_integral(), 106.857, 0.01);

    il_vec3 c555 = il_cie_cmf(555.0);
    CHECK_NEAR(c555.y, 1.0, 1e-6);
    CHECK_NEAR(c555.x, 0.5120501, 1e-6);
    /* Peaks and a linear interpolation between 595 (1.0567) and 600 (1.0622). */
    CHECK_NEAR(il_cie_cmf(597.5).x, 0.5 * (1.0567 + 1.0622), 1e-6);
    CHECK_NEAR(il_cie_cmf(445.0).z, 1.7826, 1e-6);
    /* Zero outside the table. */
    CHECK(il_cie_cmf(300.0).y == 0.0f);
    CHECK(il_cie_cmf(900.0).x == 0.0f);

    CHECK_NEAR(il_cie_d65(560.0), 100.0, 1e-9);
    CHECK_NEAR(il_cie_d65(562.5), 0.5 * (100.0 + 98.1671), 1e-9);
    CHECK(il_cie_d65(350.0) == 0.0);
}

static void test_matrix(void)
{
    /* D65 white point (CIE 15: x = 0.31271, y = 0.32902 -> X = 0.95047, Z = 1.08883). */
    il_vec3 w = il_xyz_to_rec709((il_vec3){0.95047f, 1.0f, 1.08883f});
    CHECK_NEAR(w.x, 1.0, 1e-3);
    CHECK_NEAR(w.y, 1.0, 1e-3);
    CHECK_NEAR(w.z, 1.0, 1e-3);
    /* The Rec.709 primaries' chromaticities map to pure channels:
     * red x = 0.64, y = 0.33 (Y = 0.2126 for unit red). */
    double Y = 0.2126, x = 0.64, y = 0.33;
    il_vec3 r = il_xyz_to_rec709((il_vec3){(float)(x * Y / y), (float)Y, (float)((1 - x - y) * Y / y)});
    CHECK_NEAR(r.x, 1.0, 2e-3);
    CHECK_NEAR(r.y, 0.0, 2e-3);
    CHECK_NEAR(r.z, 0.0, 2e-3);
}

static void test_spectra(void)
{
    /* A constant reflectance of 1 (two samples, held beyond the ends) is white. */
    const float lam2[2] = {400.0f, 700.0f};
    const float one[2] = {1.0f, 1.0f};
    il_vec3 white = il_reflectance_to_rgb(lam2, one, 2);
    CHECK_NEAR(white.x, 1.0, 1e-4);
    CHECK_NEAR(white.y, 1.0, 1e-4);
    CHECK_NEAR(white.z, 1.0, 1e-4);
    /* Linear in the reflectance: a constant 0.5 gives 0.5 grey. */
    const float half[2] = {0.5f, 0.5f};
    il_vec3 grey = il_reflectance_to_rgb(lam2, half, 2);
    CHECK_NEAR(grey.x, 0.5, 1e-4);
    CHECK_NEAR(grey.z, 0.5, 1e-4);
    /* A reflectance that only passes long wavelengths is red. */
    const float lam4[4] = {400.0f, 590.0f, 600.0f, 700.0f};
    const float redr[4] = {0.0f, 0.0f, 0.9f, 0.9f};
    il_vec3 red = il_reflectance_to_rgb(lam4, redr, 4);
    CHECK(red.x > 0.3f && red.x > 4.0f * red.y && red.x > 4.0f * red.z);

    /* The tables and the matrix agree: the D65 spectrum, integrated against
     * the CMF table, has the D65 white point and the matrix maps it to grey. */
    float lam[95], d65[95];
    for (int i = 0; i < 95; i++) {
        lam[i] = 360.0f + 5.0f * (float)i;
        d65[i] = (float)il_cie_d65(lam[i]);
    }
    il_vec3 xyz = il_spectrum_to_xyz(lam, d65, 95);
    CHECK_NEAR(xyz.x / xyz.y, 0.95047, 5e-4);
    CHECK_NEAR(xyz.z / xyz.y, 1.08883, 5e-4);
    il_vec3 d = il_xyz_to_rec709(v3_div_y(xyz));
    CHECK_NEAR(d.x, 1.0, 1e-3);
    CHECK_NEAR(d.y, 1.0, 1e-3);
    CHECK_NEAR(d.z, 1.0, 1e-3);
    /* Balanced to an equal-energy white, D65 emission is bluish. */
    il_vec3 e = il_emission_to_rgb(lam, d65, 95);
    CHECK(e.z > e.y && e.y > e.x);

    /* An equal-energy spectrum of value 3 has Y = 3 integral(ybar) and, as an
     * emitter, radiance exactly (3,3,3). */
    const float three[2] = {360.0f, 830.0f};
    const float v3v[2] = {3.0f, 3.0f};
    il_vec3 ee = il_spectrum_to_xyz(three, v3v, 2);
    CHECK_REL(ee.y / il_cie_y_integral(), 3.0, 1e-6);
    il_vec3 eer = il_emission_to_rgb(three, v3v, 2);
    CHECK_NEAR(eer.x, 3.0, 1e-4);
    CHECK_NEAR(eer.y, 3.0, 1e-4);
    CHECK_NEAR(eer.z, 3.0, 1e-4);
    /* ...while its colorimetric Rec.709 value is pinkish (E is not D65). */
    il_vec3 eraw = il_xyz_to_rec709(v3_div_y(ee));
    CHECK_NEAR(eraw.x, 1.2, 0.02);
    CHECK_NEAR(eraw.z, 0.90, 0.02);

    /* The Cornell light spectrum (0, 8, 15.6, 18.4 at 400..700 nm) gives the
     * radiance renderers commonly use, about (17, 12, 4). */
    const float cl[4] = {400.0f, 500.0f, 600.0f, 700.0f}, cv[4] = {0.0f, 8.0f, 15.6f, 18.4f};
    il_vec3 c = il_emission_to_rgb(cl, cv, 4);
    CHECK_REL(c.x, 17.0, 0.05);
    CHECK_REL(c.y, 12.0, 0.1);
    CHECK(c.z > 2.5f && c.z < 4.5f);

    /* Integration is exact for piecewise-linear input: a box 550-560 nm of
     * height 1 gives Y = integral of ybar over 550-560 from the table:
     * 2.5 * (0.9949501 + 1) + 2.5 * (1 + 0.995) = 9.9748753, whatever the
     * jumps at the box edges (samples at 550 and 560 with zero beyond). */
    const float boxl[2] = {550.0f, 560.0f};
    const float boxv[2] = {1.0f, 1.0f};
    CHECK_NEAR(il_spectrum_to_xyz(boxl, boxv, 2).y, 9.9748753, 1e-5);
    /* ...and a triangle 0 -> 1 -> 0 over 550-555-560 (product of two linear
     * functions on each 5 nm piece): integral over [550,555] of
     * (t/5)(0.99495 + (1-0.99495) t/5) dt + mirrored piece. */
    const float tril[3] = {550.0f, 555.0f, 560.0f};
    const float triv[3] = {0.0f, 1.0f, 0.0f};
    double a0 = 0.9949501, a1 = 1.0, b1 = 0.995;
    double left = 5.0 * (a0 / 2.0 + (a1 - a0) / 3.0);  /* int_0^1 s (a0 + (a1-a0) s) ds * 5 */
    double right = 5.0 * (a1 / 2.0 + (b1 - a1) / 6.0); /* int_0^1 (1-s)(a1 + (b1-a1) s) ds * 5 */
    CHECK_NEAR(il_spectrum_to_xyz(tril, triv, 3).y, left + right, 1e-5);

    /* Evaluation: interpolation, zero or held outside. */
    CHECK_NEAR(il_spectrum_eval(tril, triv, 3, 552.5, 0), 0.5, 1e-6);
    CHECK_NEAR(il_spectrum_eval(tril, triv, 3, 560.0, 0), 0.0, 1e-6);
    CHECK_NEAR(il_spectrum_eval(lam2, half, 2, 800.0, 1), 0.5, 1e-6);
    CHECK_NEAR(il_spectrum_eval(lam2, half, 2, 800.0, 0), 0.0, 1e-6);
    CHECK(il_spectrum_to_xyz(lam2, half, 0).y == 0.0f);
}

int main(void)
{
    test_tables();
    test_matrix();
    test_spectra();
    return check_report();
}
