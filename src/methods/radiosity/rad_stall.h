/* When a radiosity solve stops converging (rad_solve_shoot.c,
 * rad_solve_gather.c, the GPU's and shared kernel's Jacobi sweeps in
 * kernel/kernel_radiosity_scene.c and cuda/radiosity_kernel.cu, and the
 * sweeps of hierarchical radiosity in methods/hr/hr_solve.c; plain C that
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
 * 10 n shots cut the unshot power by at least a factor exp(-10 (1 - rho));
 * a Jacobi sweep multiplies the power it changes by at most rho
 * (reciprocity, rows summing to at most 1), so 10 sweeps by rho^10.  Both
 * are below 0.999 for any rho below 0.9999.  So a window of 10 n shots or 10
 * sweeps that lowers the measure by less than 0.1% is a stall.  The test
 * compares the measure's mean over each window with its mean over the one
 * before (if every step of a window is below 0.999 times the step a window
 * earlier, so is the mean), which noise cannot pass for a stall as easily
 * as single values.
 *
 * The first window is left out: Gauss-Seidel's first sweeps raise the
 * measure above its start (a sweep's change counts the updates it made
 * itself), and at albedo 0.999 the mean of its first 10 sweeps lies below
 * that of the next 10.  The second window gives the reference, so a stall
 * is seen after three windows at the earliest: 30 sweeps or 30 n shots.
 *
 * The measure must be free of rounding noise near rho = 1.  A first version
 * compared single values 10 sweeps apart while the float Jacobi sweeps (the
 * shared kernel, the GPU) measured their change as a difference of nearly
 * equal floats (L near 1000 changing by 0.1 to 0.01 a sweep at rho = 0.999,
 * a jitter of 0.5% to 10%); it stopped such a solve as stalled after 2,040
 * sweeps.  The float Jacobi sweeps now run in increments, and the CPU's
 * gathering solvers keep the radiance in double while they solve
 * (kernel/kernel_radiosity.h, rad_solve_gather.c). */
#define IL_RAD_STALL_WINDOW 10u /* sweeps, or shots per patch, in a window */
#define IL_RAD_STALL_DROP 0.999  /* a window's mean must fall below this times the last */

typedef struct il_rad_stall {
    uint32_t window;           /* steps per window */
    uint32_t last_step;        /* the step that ended the last window */
    double sum;                /* the measures seen in this window */
    uint32_t count;            /* how many */
    uint32_t windows;          /* how many windows have ended */
    double last_mean;          /* the last window's mean */
} il_rad_stall;

/* units: 1 for gathering sweeps, the number of patches for shots. */
static inline void il_rad_stall_start(il_rad_stall *s, uint32_t units)
{
    uint64_t window = (uint64_t)IL_RAD_STALL_WINDOW * (units ? units : 1);
    s->window = window < UINT32_MAX ? (uint32_t)window : UINT32_MAX;
    s->last_step = 0;
    s->sum = 0.0;
    s->count = 0;
    s->windows = 0;
    s->last_mean = 0.0;
}

/* Adds the measure `fraction` after `steps` steps; true when the window it
 * ends, the third or a later one, had a mean less than 0.1% below the window
 * before. */
static inline bool il_rad_stalled(il_rad_stall *s, uint32_t steps, double fraction)
{
    s->sum += fraction;
    s->count++;
    if (steps - s->last_step < s->window)
        return false;
    double mean = s->sum / s->count;
    bool stalled = ++s->windows >= 3 && !(mean < IL_RAD_STALL_DROP * s->last_mean);
    s->last_step = steps;
    s->sum = 0.0;
    s->count = 0;
    s->last_mean = mean;
    return stalled;
}

#endif
