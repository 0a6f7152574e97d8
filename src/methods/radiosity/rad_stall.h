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
 * 10 n shots cut the unshot power by at least a factor exp(-10 (1 - rho));
 * a Jacobi sweep multiplies the power it changes by at most rho
 * (reciprocity, rows summing to at most 1), so 10 sweeps by rho^10.  Both
 * are below 0.999 for any rho below 0.9999.  So a window of 10 n shots or 10
 * sweeps that lowers the measure by less than 0.1% is a stall.  The first
 * window only takes the reference: Gauss-Seidel's first sweeps raise the
 * measure above its start (a sweep's change counts the updates it made
 * itself), so a stall is seen after two windows at the earliest. */
#define IL_RAD_STALL_WINDOW 10u /* sweeps, or shots per patch, between checks */

typedef struct il_rad_stall {
    uint32_t window;           /* steps per check */
    uint32_t last_step;        /* the step of the last check */
    double last_fraction;      /* the measure then */
} il_rad_stall;

/* units: 1 for gathering sweeps, the number of patches for shots. */
static inline void il_rad_stall_start(il_rad_stall *s, uint32_t units)
{
    uint64_t window = (uint64_t)IL_RAD_STALL_WINDOW * (units ? units : 1);
    s->window = window < UINT32_MAX ? (uint32_t)window : UINT32_MAX;
    s->last_step = 0;
    s->last_fraction = -1.0; /* none yet */
}

/* True when the window that ends at `steps` lowered the measure by < 0.1%. */
static inline bool il_rad_stalled(il_rad_stall *s, uint32_t steps, double fraction)
{
    if (steps - s->last_step < s->window)
        return false;
    bool stalled = s->last_fraction >= 0.0 && !(fraction < 0.999 * s->last_fraction);
    s->last_step = steps;
    s->last_fraction = fraction;
    return stalled;
}

#endif
