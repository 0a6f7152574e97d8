/* Energy-preserving bloom (glare) on an HDR image (docs/tonemapping.md#bloom).
 *
 * The part of each pixel's light above a luminance threshold is, by a
 * fraction `strength`, taken out of the pixel, spread by a wide normalised
 * kernel and added back.  The kernel is a sum of IL_BLOOM_LEVELS Gaussians
 * with octave-spaced widths sigma_k = radius * 2^(k - IL_BLOOM_LEVELS + 1)
 * and equal weights, whose sum falls off about as 1/r^2 between radius/8 and
 * radius, like the 1/theta^2 term of the eye's point-spread function in
 * Spencer et al. 1995 ("Physically-Based Glare Effects for Digital Images",
 * whose scattering terms fall off as 1/theta^2 and 1/theta^3).
 *
 * Each Gaussian is three cascaded extended box filters (Wells 1986,
 * "Efficient synthesis of Gaussian filters by cascaded uniform filters";
 * Gwosdek, Grewenig, Bruhn, Weickert 2011, "Theoretical foundations of
 * Gaussian convolution by extended box filtering": a box of 2r+1 ones and a
 * fractional weight alpha at each end, so the variance is exact), run as
 * separable running sums: the cost per pixel does not depend on the radius.
 * Level k is blurred on a pyramid level 2^j times coarser, the coarsest
 * where sigma_k is still IL_BLOOM_MIN_SIGMA of its pixels or more (as in
 * Burt and Adelson 1983: the wide Gaussians cost a 4^-j fraction).  The
 * pyramid moves light, not averages.  Up, a coarse pixel's light is spread
 * over the fine pixels at offsets -2..2 from it with the cubic B-spline
 * subdivision weights (1, 4, 6, 4, 1)/16 (Lane and Riesenfeld 1980), a
 * smooth interpolation; down is its transpose: a fine pixel's light goes to
 * the coarse pixel at it (6/8) and the two beside (1/8 each), or half to
 * each of the two coarse pixels around it.  Each step keeps a pixel's
 * centroid and adds a variance of 1 pixel^2 of the finer level whatever the
 * pixel's position; the glare of one pixel is symmetric about it when the
 * pixel lies on the coarsest level's grid and nearly so elsewhere (the
 * tests measure both).
 *
 * Every step (box pass, down, up) is normalised per *source* over the pixels
 * it reaches inside the image, so no light leaves at the borders: each
 * channel's sum over the image is preserved (to float rounding). */
#ifndef IL_IMAGE_BLOOM_H
#define IL_IMAGE_BLOOM_H

#include <stdint.h>

#include "illum/illum.h"

#define IL_BLOOM_LEVELS 4
#define IL_BLOOM_PASSES 3
#define IL_BLOOM_MIN_SIGMA 1.75

/* The discrete kernel used for one radius. */
typedef struct il_bloom_kernel {
    int res[IL_BLOOM_LEVELS];   /* pyramid level: 2^res image pixels per pixel */
    /* Level k's incremental blur (on level k-1 brought down to res[k]):
     * IL_BLOOM_PASSES extended boxes of radius r and end weight alpha, in
     * pixels of res[k]. */
    int box_radius[IL_BLOOM_LEVELS];
    double box_alpha[IL_BLOOM_LEVELS];
    double variance[IL_BLOOM_LEVELS]; /* level k's variance per axis, image pixels^2 */
    double weight[IL_BLOOM_LEVELS];   /* sums to 1 */
} il_bloom_kernel;

/* The kernel for a widest-Gaussian standard deviation of `sigma` pixels. */
void il_bloom_kernel_make(double sigma, il_bloom_kernel *k);

/* Applies bloom in place to `rgb` (width x height pixels, 3 floats each,
 * finite and non-negative): strength in [0,1], threshold > 0 (luminance),
 * sigma >= 0 pixels (the widest Gaussian).  Nothing changes, bit for bit,
 * when no pixel's luminance exceeds the threshold. */
il_status il_bloom_apply(float *rgb, uint32_t width, uint32_t height, double strength,
                         double threshold, double sigma, il_error *err);

#endif
