/* Spectral colour: CIE 1931 colour-matching functions, D65, spectrum -> XYZ ->
 * linear Rec.709.  See color.h for the conventions. */
#include "core/color.h"

#include <math.h>

#define IL_CIE_N 95 /* (830 - 360) / 5 + 1 */

/* CIE 1931 2-degree standard colorimetric observer, xbar ybar zbar, 360-830 nm every
 * 5 nm: the 5 nm rows, values unchanged, of the CIE's 1 nm table
 * "CIE_xyz_1931_2deg.csv" (CIE, "Colour-matching functions of CIE 1931 standard
 * colorimetric observer", data set, 2019, doi:10.25039/CIE.DS.xvudnb9b; the same
 * numbers as CVRL's ciexyz31_1 and the 5 nm table of CIE 15:2004), read from a
 * public copy of that file.  Checks: sum(ybar)*5 nm = 106.857,
 * sum(xbar)*5 = 106.866, sum(zbar)*5 = 106.893 (tests/unit/test_color.c). */
static const double cie_cmf[IL_CIE_N][3] = {
    {0.0001299, 0.000003917, 0.0006061}, /* 360 */
    {0.0002321, 0.000006965, 0.001086}, /* 365 */
    {0.0004149, 0.00001239, 0.001946}, /* 370 */
    {0.0007416, 0.00002202, 0.003486}, /* 375 */
    {0.001368, 0.000039, 0.006450001}, /* 380 */
    {0.002236, 0.000064, 0.01054999}, /* 385 */
    {0.004243, 0.00012, 0.02005001}, /* 390 */
    {0.00765, 0.000217, 0.03621}, /* 395 */
    {0.01431, 0.000396, 0.06785001}, /* 400 */
    {0.02319, 0.00064, 0.1102}, /* 405 */
    {0.04351, 0.00121, 0.2074}, /* 410 */
    {0.07763, 0.00218, 0.3713}, /* 415 */
    {0.13438, 0.004, 0.6456}, /* 420 */
    {0.21477, 0.0073, 1.0390501}, /* 425 */
    {0.2839, 0.0116, 1.3856}, /* 430 */
    {0.3285, 0.01684, 1.62296}, /* 435 */
    {0.34828, 0.023, 1.74706}, /* 440 */
    {0.34806, 0.0298, 1.7826}, /* 445 */
    {0.3362, 0.038, 1.77211}, /* 450 */
    {0.3187, 0.048, 1.7441}, /* 455 */
    {0.2908, 0.06, 1.6692}, /* 460 */
    {0.2511, 0.0739, 1.5281}, /* 465 */
    {0.19536, 0.09098, 1.28764}, /* 470 */
    {0.1421, 0.1126, 1.0419}, /* 475 */
    {0.09564, 0.13902, 0.8129501}, /* 480 */
    {0.05795001, 0.1693, 0.6162}, /* 485 */
    {0.03201, 0.20802, 0.46518}, /* 490 */
    {0.0147, 0.2586, 0.3533}, /* 495 */
    {0.0049, 0.323, 0.272}, /* 500 */
    {0.0024, 0.4073, 0.2123}, /* 505 */
    {0.0093, 0.503, 0.1582}, /* 510 */
    {0.0291, 0.6082, 0.1117}, /* 515 */
    {0.06327, 0.71, 0.07824999}, /* 520 */
    {0.1096, 0.7932, 0.05725001}, /* 525 */
    {0.1655, 0.862, 0.04216}, /* 530 */
    {0.2257499, 0.9148501, 0.02984}, /* 535 */
    {0.2904, 0.954, 0.0203}, /* 540 */
    {0.3597, 0.9803, 0.0134}, /* 545 */
    {0.4334499, 0.9949501, 0.008749999}, /* 550 */
    {0.5120501, 1, 0.005749999}, /* 555 */
    {0.5945, 0.995, 0.0039}, /* 560 */
    {0.6784, 0.9786, 0.002749999}, /* 565 */
    {0.7621, 0.952, 0.0021}, /* 570 */
    {0.8425, 0.9154, 0.0018}, /* 575 */
    {0.9163, 0.87, 0.001650001}, /* 580 */
    {0.9786, 0.8163, 0.0014}, /* 585 */
    {1.0263, 0.757, 0.0011}, /* 590 */
    {1.0567, 0.6949, 0.001}, /* 595 */
    {1.0622, 0.631, 0.0008}, /* 600 */
    {1.0456, 0.5668, 0.0006}, /* 605 */
    {1.0026, 0.503, 0.00034}, /* 610 */
    {0.9384, 0.4412, 0.00024}, /* 615 */
    {0.8544499, 0.381, 0.00019}, /* 620 */
    {0.7514, 0.321, 0.0001}, /* 625 */
    {0.6424, 0.265, 0.00005}, /* 630 */
    {0.5419, 0.217, 0.00003}, /* 635 */
    {0.4479, 0.175, 0.00002}, /* 640 */
    {0.3608, 0.1382, 0.00001}, /* 645 */
    {0.2835, 0.107, 0}, /* 650 */
    {0.2187, 0.0816, 0}, /* 655 */
    {0.1649, 0.061, 0}, /* 660 */
    {0.1212, 0.04458, 0}, /* 665 */
    {0.0874, 0.032, 0}, /* 670 */
    {0.0636, 0.0232, 0}, /* 675 */
    {0.04677, 0.017, 0}, /* 680 */
    {0.0329, 0.01192, 0}, /* 685 */
    {0.0227, 0.00821, 0}, /* 690 */
    {0.01584, 0.005723, 0}, /* 695 */
    {0.01135916, 0.004102, 0}, /* 700 */
    {0.008110916, 0.002929, 0}, /* 705 */
    {0.005790346, 0.002091, 0}, /* 710 */
    {0.004109457, 0.001484, 0}, /* 715 */
    {0.002899327, 0.001047, 0}, /* 720 */
    {0.00204919, 0.00074, 0}, /* 725 */
    {0.001439971, 0.00052, 0}, /* 730 */
    {0.000999949, 0.0003611, 0}, /* 735 */
    {0.000690079, 0.0002492, 0}, /* 740 */
    {0.000476021, 0.0001719, 0}, /* 745 */
    {0.000332301, 0.00012, 0}, /* 750 */
    {0.000234826, 0.0000848, 0}, /* 755 */
    {0.000166151, 0.00006, 0}, /* 760 */
    {0.000117413, 0.0000424, 0}, /* 765 */
    {0.0000830753, 0.00003, 0}, /* 770 */
    {0.0000587065, 0.0000212, 0}, /* 775 */
    {0.0000415099, 0.00001499, 0}, /* 780 */
    {0.0000293533, 0.0000106, 0}, /* 785 */
    {0.0000206738, 0.0000074657, 0}, /* 790 */
    {0.0000145598, 0.0000052578, 0}, /* 795 */
    {0.000010254, 0.0000037029, 0}, /* 800 */
    {0.00000722146, 0.0000026078, 0}, /* 805 */
    {0.00000508587, 0.0000018366, 0}, /* 810 */
    {0.00000358165, 0.0000012934, 0}, /* 815 */
    {0.00000252253, 0.00000091093, 0}, /* 820 */
    {0.00000177651, 0.00000064153, 0}, /* 825 */
    {0.00000125114, 0.00000045181, 0}, /* 830 */
};

/* CIE standard illuminant D65, relative spectral power distribution, 360-830 nm every
 * 5 nm: the 5 nm rows of the CIE's "CIE_std_illum_D65.csv" (CIE, "CIE standard
 * illuminant D65", data set, 2019, doi:10.25039/CIE.DS.hjfjmt59; ISO 11664-2 / CIE S 014-2),
 * values unchanged, read from a public copy of that file.  With the table above
 * its white point is X/Y = 0.95047, Z/Y = 1.08897 (the 1 nm tables give 1.08883).
 * The conversions below do not use it (they balance to an equal-energy white);
 * it checks the tables against the matrix, whose white is D65, and is there
 * for callers who want D65-referred colour. */
static const double cie_d65[IL_CIE_N] = {
    46.6383, 49.3637, 52.0891, 51.0323, 49.9755, 52.3118, 54.6482, 68.7015,
    82.7549, 87.1204, 91.486, 92.4589, 93.4318, 90.057, 86.6823, 95.7736,
    104.865, 110.936, 117.008, 117.41, 117.812, 116.336, 114.861, 115.392,
    115.923, 112.367, 108.811, 109.082, 109.354, 108.578, 107.802, 106.296,
    104.79, 106.239, 107.689, 106.047, 104.405, 104.225, 104.046, 102.023,
    100, 98.1671, 96.3342, 96.0611, 95.788, 92.2368, 88.6856, 89.3459,
    90.0062, 89.8026, 89.5991, 88.6489, 87.6987, 85.4936, 83.2886, 83.4939,
    83.6992, 81.863, 80.0268, 80.1207, 80.2146, 81.2462, 82.2778, 80.281,
    78.2842, 74.0027, 69.7213, 70.6652, 71.6091, 72.979, 74.349, 67.9765,
    61.604, 65.7448, 69.8856, 72.4863, 75.087, 69.3398, 63.5927, 55.0054,
    46.4182, 56.6118, 66.8054, 65.0941, 63.3828, 63.8434, 64.304, 61.8779,
    59.4519, 55.7054, 51.959, 54.6998, 57.4406, 58.8765, 60.3125,
};

typedef struct dxyz { double x, y, z; } dxyz;

/* The table segment [i, i+1] holding `lambda`; -1 outside the table. */
static int table_segment(double lambda, double *t)
{
    double u = (lambda - IL_CIE_LAMBDA_MIN) / IL_CIE_LAMBDA_STEP;
    if (!(u >= 0.0) || u > (double)(IL_CIE_N - 1))
        return -1;
    int i = (int)u;
    if (i > IL_CIE_N - 2)
        i = IL_CIE_N - 2;
    *t = u - (double)i;
    return i;
}

il_vec3 il_cie_cmf(double lambda_nm)
{
    double t;
    int i = table_segment(lambda_nm, &t);
    if (i < 0)
        return (il_vec3){0.0f, 0.0f, 0.0f};
    const double *a = cie_cmf[i], *b = cie_cmf[i + 1];
    return (il_vec3){(float)(a[0] + (b[0] - a[0]) * t), (float)(a[1] + (b[1] - a[1]) * t),
                     (float)(a[2] + (b[2] - a[2]) * t)};
}

double il_cie_d65(double lambda_nm)
{
    double t;
    int i = table_segment(lambda_nm, &t);
    if (i < 0)
        return 0.0;
    return cie_d65[i] + (cie_d65[i + 1] - cie_d65[i]) * t;
}

/* Index i of the sample segment [lambda[i], lambda[i+1]] holding x (binary
 * search); -1 before the first sample, n-1 after the last.  Needs n >= 2. */
static long spectrum_segment(const float *lambda, size_t n, double x)
{
    if (x < lambda[0])
        return -1;
    if (x > lambda[n - 1])
        return (long)n - 1;
    size_t lo = 0, hi = n - 1; /* lambda[lo] <= x <= lambda[hi] */
    while (hi - lo > 1) {
        size_t mid = (lo + hi) / 2;
        if (x < lambda[mid])
            hi = mid;
        else
            lo = mid;
    }
    return (long)lo;
}

/* The linear piece of the spectrum on segment `seg` (from spectrum_segment),
 * extended to x; outside the samples zero or the end value. */
static double spectrum_piece(const float *lambda, const float *value, size_t n, long seg, double x,
                             int hold_ends)
{
    if (seg < 0)
        return hold_ends ? value[0] : 0.0;
    if (seg >= (long)n - 1)
        return hold_ends ? value[n - 1] : 0.0;
    double l0 = lambda[seg], l1 = lambda[seg + 1];
    return value[seg] + (value[seg + 1] - value[seg]) * (x - l0) / (l1 - l0);
}

double il_spectrum_eval(const float *lambda_nm, const float *value, size_t n, double lambda,
                        int hold_ends)
{
    if (n == 0)
        return 0.0;
    if (n == 1)
        return (hold_ends || lambda == lambda_nm[0]) ? value[0] : 0.0;
    return spectrum_piece(lambda_nm, value, n, spectrum_segment(lambda_nm, n, lambda), lambda,
                          hold_ends);
}

/* Integral over 360-830 nm of S(l) * cmf(l), S piecewise linear (n == 0:
 * S = 1).  The interval is cut at every table wavelength and every sample
 * wavelength of S; on each piece both factors are linear, so the integrand is
 * a quadratic and Simpson's rule integrates it exactly.  Each factor is
 * evaluated from the linear piece holding the piece's midpoint, so jumps at
 * S's end samples (S zero outside) are handled exactly too. */
static dxyz integrate(const float *lambda, const float *value, size_t n, int hold_ends)
{
    dxyz sum = {0.0, 0.0, 0.0};
    size_t j = 0;
    double a = IL_CIE_LAMBDA_MIN;
    for (int k = 1; k < IL_CIE_N; k++) {
        double grid = IL_CIE_LAMBDA_MIN + IL_CIE_LAMBDA_STEP * k;
        const double *c0 = cie_cmf[k - 1], *c1 = cie_cmf[k];
        while (a < grid) {
            while (j < n && lambda[j] <= a)
                j++;
            double b = (j < n && lambda[j] < grid) ? lambda[j] : grid;
            double m = 0.5 * (a + b), xs[3] = {a, m, b}, wsimp[3] = {1.0, 4.0, 1.0};
            long seg = n >= 2 ? spectrum_segment(lambda, n, m) : (n && m > lambda[0] ? 0 : -1);
            for (int q = 0; q < 3; q++) {
                double t = (xs[q] - (grid - IL_CIE_LAMBDA_STEP)) / IL_CIE_LAMBDA_STEP;
                double s = n ? spectrum_piece(lambda, value, n, seg, xs[q], hold_ends) : 1.0;
                double w = wsimp[q] * s * (b - a) / 6.0;
                sum.x += w * (c0[0] + (c1[0] - c0[0]) * t);
                sum.y += w * (c0[1] + (c1[1] - c0[1]) * t);
                sum.z += w * (c0[2] + (c1[2] - c0[2]) * t);
            }
            a = b;
        }
    }
    return sum;
}

double il_cie_y_integral(void)
{
    return integrate(NULL, NULL, 0, 0).y;
}

il_vec3 il_spectrum_to_xyz(const float *lambda_nm, const float *value, size_t n)
{
    if (n == 0)
        return (il_vec3){0.0f, 0.0f, 0.0f};
    dxyz s = integrate(lambda_nm, value, n, 0);
    return (il_vec3){(float)s.x, (float)s.y, (float)s.z};
}

/* XYZ -> linear sRGB/Rec.709 primaries, D65 white: IEC 61966-2-1:1999, section
 * 5.2, equation (7) (the inverse of the matrix built from the BT.709 primaries). */
static dxyz xyz_to_rec709(dxyz c)
{
    return (dxyz){3.2406 * c.x - 1.5372 * c.y - 0.4986 * c.z,
                  -0.9689 * c.x + 1.8758 * c.y + 0.0415 * c.z,
                  0.0557 * c.x - 0.2040 * c.y + 1.0570 * c.z};
}

il_vec3 il_xyz_to_rec709(il_vec3 xyz)
{
    dxyz r = xyz_to_rec709((dxyz){xyz.x, xyz.y, xyz.z});
    return (il_vec3){(float)r.x, (float)r.y, (float)r.z};
}

/* White-balanced conversion (docs/builtin-scenes.md): linear Rec.709 of the
 * spectrum, divided per channel by that of the equal-energy spectrum of value
 * 1 (illuminant E), RGB_c = (M XYZ[S])_c / (M XYZ[1])_c.  A flat spectrum of
 * value c becomes exactly (c, c, c): a flat reflectance is grey and a
 * reflectance of 1 is (1,1,1); an emitter of flat spectral radiance c has
 * radiance c in every channel.  The division is a von Kries-style white
 * balance in RGB (the camera's white is E); for E itself M XYZ is
 * (1.200, 0.950, 0.904) x integral(ybar) before the division. */
static il_vec3 white_balanced(const float *lambda_nm, const float *value, size_t n, int hold_ends)
{
    if (n == 0)
        return (il_vec3){0.0f, 0.0f, 0.0f};
    dxyz r = xyz_to_rec709(integrate(lambda_nm, value, n, hold_ends));
    dxyz w = xyz_to_rec709(integrate(NULL, NULL, 0, 0));
    return (il_vec3){(float)(r.x / w.x), (float)(r.y / w.y), (float)(r.z / w.z)};
}

il_vec3 il_reflectance_to_rgb(const float *lambda_nm, const float *value, size_t n)
{
    return white_balanced(lambda_nm, value, n, 1);
}

il_vec3 il_emission_to_rgb(const float *lambda_nm, const float *value, size_t n)
{
    return white_balanced(lambda_nm, value, n, 0);
}
