/* When a radiosity solve stops converging (rad_solve_shoot.c,
 * rad_solve_gather.c, and the GPU's and shared kernel's Jacobi sweeps in
 * kernel/kernel_radiosity_scene.c and cuda/radiosity_kernel.cu; plain C that
 * C++ compiles too). */
#ifndef IL_METHODS_RADIOSITY_RAD_STALL_H
#define IL_METHODS_RADIOSITY_RAD_STALL_H

#include <stdbool.h>
#include <stdint.h>

/* Stall detection.  Light that cannot leave the scene (a closed room whose
 * albedo is 1) has no finite solution: the convergence measure stays where
 * it is and the solve would never end.  With every albedo at most rho < 1 it
 * cannot stall: a shot of the patch with the most unshot power (at least the
 * mean of n patches) removes that power and gives back at most rho of it, so
 * 100 n shots cut the unshot power by at least a factor exp(-100 (1 - rho));
 * a Jacobi sweep multiplies the power it changes by at most rho
 * (reciprocity, rows summing to at most 1), so 100 sweeps by rho^100.  Both
 * are below 0.99 for any rho below 0.9999.  So a window of 100 n shots or
 * 100 sweeps that lowers the measure by less than 1% is a stall.  The test
 * compares the measure's mean over each window with its mean over the one
 * before: if every step of a window is below 0.99 times the step a window
 * earlier, so is the mean.
 *
 * Why means over so long a window: noise in the measure must not look like
 * a stall.  The first version compared single values 10 sweeps apart (a
 * true drop of 1% at rho = 0.999), and the shared kernel's float sweeps,
 * which then measured their change as a difference of nearly equal floats
 * (L near 1000 changing by 0.1 to 0.01 a sweep, a jitter of 0.5% to 10%),
 * stopped such a solve as stalled after 2,040 sweeps.  The Jacobi sweeps now
 * run in increments and Gauss-Seidel forms its change in double, so the
 * measure is smooth (rad_solve_gather.c, kernel/kernel_radiosity.h); the
 * window of 100 and the means stay as the margin, a true drop of 9.5% at
 * rho = 0.999 against noise that averages out.
 *
 * The first window only takes the reference: Gauss-Seidel's first sweeps
 * raise the measure above its start (a sweep's change counts the updates it
 * made itself), so a stall is seen after two windows at the earliest. */
#define IL_RAD_STALL_WINDOW 100u /* sweeps, or shots per patch, in a window */
#define IL_RAD_STALL_DROP 0.99   /* a window's mean must fall below this times the last */

typedef struct il_rad_stall {
    uint32_t window;           /* steps per window */
    uint32_t last_step;        /* the step that ended the last window */
    double sum;                /* the measures seen in this window */
    uint32_t count;            /* how many */
    double last_mean;          /* the last window's mean; < 0: none yet */
} il_rad_stall;

/* units: 1 for gathering sweeps, the number of patches for shots. */
static inline void il_rad_stall_start(il_rad_stall *s, uint32_t units)
{
    uint64_t window = (uint64_t)IL_RAD_STALL_WINDOW * (units ? units : 1);
    s->window = window < UINT32_MAX ? (uint32_t)window : UINT32_MAX;
    s->last_step = 0;
    s->sum = 0.0;
    s->count = 0;
    s->last_mean = -1.0;
}

/* Adds the measure `fraction` after `steps` steps; true when the window it
 * ends had a mean less than 1% below the window before. */
static inline bool il_rad_stalled(il_rad_stall *s, uint32_t steps, double fraction)
{
    s->sum += fraction;
    s->count++;
    if (steps - s->last_step < s->window)
        return false;
    double mean = s->sum / s->count;
    bool stalled = s->last_mean >= 0.0 && !(mean < IL_RAD_STALL_DROP * s->last_mean);
    s->last_step = steps;
    s->sum = 0.0;
    s->count = 0;
    s->last_mean = mean;
    return stalled;
}

#endif
