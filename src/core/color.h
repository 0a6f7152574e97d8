/* Spectral colour: the CIE 1931 2-degree standard observer, CIE illuminant D65,
 * and conversion of spectra to linear Rec.709 RGB (the engine's colour space).
 *
 * A spectrum is given as samples (lambda_nm[i], value[i]), i < n, with
 * lambda strictly ascending, and is piecewise linear between them.
 *
 * Conversions (docs/builtin-scenes.md explains the choices):
 * - il_spectrum_to_xyz:      XYZ = integral of S(l) * (xbar, ybar, zbar)(l) dl,
 *                            S zero outside its samples (no 683 lm/W factor).
 * - il_xyz_to_rec709:        the IEC 61966-2-1 (sRGB) / ITU-R BT.709 matrix, D65 white.
 * - il_reflectance_to_rgb,
 *   il_emission_to_rgb:      white-balanced to an equal-energy white (illuminant E):
 *                            RGB_c = (M XYZ[S])_c / (M XYZ[1])_c, so a flat spectrum
 *                            of value c gives exactly (c, c, c).  A reflectance is
 *                            held constant beyond its end samples, an emission is
 *                            zero there.
 */
#ifndef IL_CORE_COLOR_H
#define IL_CORE_COLOR_H

#include <stddef.h>
#include "illum/illum.h"

/* Photometric to radiometric: 683 lm/W, the luminous efficacy of 555 nm light
 * that defines the candela (SI brochure, 9th ed., 2.3.1); the constant
 * Blender's glTF importer uses (PBR_WATTS_TO_LUMENS).  The loaders divide
 * candela and lux by it; illuminance readings multiply by it. */
#define IL_LUMENS_PER_WATT 683.0f

/* Range and step of the embedded tables (nm). */
#define IL_CIE_LAMBDA_MIN 360.0
#define IL_CIE_LAMBDA_MAX 830.0
#define IL_CIE_LAMBDA_STEP 5.0

/* CIE 1931 2-degree colour-matching functions at `lambda_nm`, linearly
 * interpolated in the 5 nm table; zero outside 360-830 nm. */
il_vec3 il_cie_cmf(double lambda_nm);
/* CIE standard illuminant D65, relative spectral power (100 at 560 nm),
 * linearly interpolated; zero outside 360-830 nm. */
double il_cie_d65(double lambda_nm);
/* Integral of ybar over the table (nm), about 106.857. */
double il_cie_y_integral(void);

/* The piecewise-linear spectrum at `lambda_nm`: zero outside its samples, or
 * held at the end values when `hold_ends`. */
double il_spectrum_eval(const float *lambda_nm, const float *value, size_t n, double lambda,
                        int hold_ends);

/* XYZ of a spectrum (its values times nm). */
il_vec3 il_spectrum_to_xyz(const float *lambda_nm, const float *value, size_t n);

/* Linear Rec.709 RGB from CIE XYZ (IEC 61966-2-1). */
il_vec3 il_xyz_to_rec709(il_vec3 xyz);

/* Diffuse albedo in linear Rec.709 of a reflectance spectrum (0..1 values);
 * a reflectance of 1 gives (1,1,1). */
il_vec3 il_reflectance_to_rgb(const float *lambda_nm, const float *value, size_t n);

/* Radiance RGB of an emission spectrum: spectral radiance in W/(sr m^2 nm)
 * in, W/(sr m^2) per channel out, scaled so that a flat spectral radiance c
 * gives RGB radiance (c, c, c) (luminance c, as the 1/integral(ybar)
 * normalisation of pbrt and Mitsuba gives for a flat spectrum). */
il_vec3 il_emission_to_rgb(const float *lambda_nm, const float *value, size_t n);

#endif
