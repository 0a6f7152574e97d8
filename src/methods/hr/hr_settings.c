/* il_hr_desc -> il_hr_settings: defaults and range checks.
 *
 * The epsilons are relative (docs/hierarchical-radiosity.md):
 *   bf_eps:    SPLASH-2 refines while F * B > BFepsilon with B in absolute
 *              units; we divide B by the scene's mean emitted radiance
 *              B_ref (hr_refine.c), so the lights' power does not matter
 *              (default 0.015, SPLASH-2's value);
 *   area_eps:  SPLASH-2's minimum area 2000 in a room about 1700 units wide
 *              becomes a fraction of the scene's bounding-box diagonal
 *              squared, 2000 / 1700^2, so the scene's units do not matter;
 *   energy_eps: SPLASH-2 stops when the relative change of the total energy
 *              falls below it; we stop when what is left of the reflected
 *              energy, estimated from its last two changes, does
 *              (hr_solve.c, energy_left), as the last change alone stops
 *              bright rooms early. */
#include <math.h>
#include <omp.h>
#include <unistd.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/hr/hr.h"

static il_status check_eps(const char *name, float v, float max, il_error *err)
{
    if (!isfinite(v) || v < 0.0f || v > max)
        return il_fail(err, IL_ERR_INVALID,
                       "hr: %s %g is out of range (0 to %g; 0 means the default)", name, (double)v,
                       (double)max);
    return IL_OK;
}

il_status il_hr_settings_resolve(const il_render_desc *desc, il_hr_settings *out, il_error *err)
{
    static const il_hr_desc none = {0};
    const il_hr_desc *d = desc->hr ? desc->hr : &none;
    il_status st;
    if ((st = check_eps("bf-eps", d->bf_eps, 1.0f, err)) != IL_OK ||
        (st = check_eps("area-eps", d->area_eps, 1.0f, err)) != IL_OK ||
        (st = check_eps("energy-eps", d->energy_eps, 1.0f, err)) != IL_OK)
        return st;
    if (d->vis_rays > IL_HR_MAX_VIS_RAYS)
        return il_fail(err, IL_ERR_INVALID,
                       "hr: vis-rays %u is out of range (1 to %u; 0 means the default 16)",
                       d->vis_rays, IL_HR_MAX_VIS_RAYS);
    if (d->max_iterations > IL_HR_MAX_ITERATIONS)
        return il_fail(err, IL_ERR_INVALID,
                       "hr: max-iterations %u is out of range (1 to %u; 0 means the default 100)",
                       d->max_iterations, IL_HR_MAX_ITERATIONS);
    if (desc->threads < 0 || desc->threads > 4096)
        return il_fail(err, IL_ERR_INVALID,
                       "hr: threads %d is out of range (1 to 4096; 0 means all cores)",
                       desc->threads);
    if ((st = il_distrib_check(desc->distrib, desc, "hr", err)) != IL_OK)
        return st;
    out->distrib = il_distrib_on(desc->distrib) ? desc->distrib : NULL;
    out->bf_eps = d->bf_eps > 0.0f ? d->bf_eps : 0.015f;
    out->area_eps = d->area_eps > 0.0f ? d->area_eps : 2000.0f / (1700.0f * 1700.0f);
    out->energy_eps = d->energy_eps > 0.0f ? d->energy_eps : 0.005f;
    out->vis_rays = d->vis_rays > 0 ? d->vis_rays : 16u;
    out->max_iterations = d->max_iterations > 0 ? d->max_iterations : 100u;
    out->seed = desc->seed;
    out->on_iteration = NULL;
    out->on_iteration_user = NULL;
    /* A process that stopped alone would leave the others waiting. */
    out->on_step = out->distrib ? NULL : d->on_step;
    out->on_step_user = out->distrib ? NULL : d->on_step_user;
    out->threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    out->link_memory_limit = UINT64_MAX;
#if defined(_SC_PHYS_PAGES) && defined(_SC_PAGESIZE)
    long pages = sysconf(_SC_PHYS_PAGES), page = sysconf(_SC_PAGESIZE);
    if (pages > 0 && page > 0)
        out->link_memory_limit = (uint64_t)pages * (uint64_t)page / 2;
#endif
    if (out->threads < 1)
        out->threads = 1;
    return IL_OK;
}
