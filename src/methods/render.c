/* il_render: checks the options and hands the work to the chosen method. */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "illum/illum.h"
#include "methods/distrib.h"
#include "methods/hr/hr.h"
#include "methods/ibl/ibl.h"
#include "methods/linespace/ls.h"
#include "methods/photon/pm.h"
#include "methods/pt/pt.h"
#include "methods/radiosity/rad.h"
#include "methods/rsm/rsm.h"
#include "scene/scene.h"

/* Limits beyond which an option is certainly a mistake (a typo, a negative
 * number read as unsigned), not a wish. */
#define IL_MAX_SPP (1u << 24)
#define IL_MAX_DEPTH 1024u
#define IL_MAX_THREADS 4096
#define IL_MAX_TIME (365.0 * 24.0 * 3600.0)

static il_status validate(const il_scene *scene, const il_film *film, const il_render_desc *d,
                          il_error *err)
{
    if (!scene)
        return il_fail(err, IL_ERR_INVALID, "render: no scene given");
    if (!film)
        return il_fail(err, IL_ERR_INVALID, "render: no film given");
    if (!d)
        return il_fail(err, IL_ERR_INVALID, "render: no render options given");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID,
                       "render: the scene is not committed (call il_scene_commit first)");
    if (il_film_width(film) == 0 || il_film_height(film) == 0)
        return il_fail(err, IL_ERR_INVALID, "render: the film has no pixels");
    if ((unsigned)d->method > IL_METHOD_RSM)
        return il_fail(err, IL_ERR_INVALID, "render: unknown method %d", (int)d->method);
    if (d->spp > IL_MAX_SPP)
        return il_fail(err, IL_ERR_INVALID, "render: spp %u is out of range (1 to %u; 0 means the default)",
                       d->spp, IL_MAX_SPP);
    if (!isfinite(d->time_limit) || d->time_limit < 0.0 || d->time_limit > IL_MAX_TIME)
        return il_fail(err, IL_ERR_INVALID,
                       "render: time limit %g s is out of range (0 to one year; 0 means none)",
                       d->time_limit);
    if (d->max_depth > IL_MAX_DEPTH)
        return il_fail(err, IL_ERR_INVALID,
                       "render: max depth %u is out of range (1 to %u; 0 means the default 8)",
                       d->max_depth, IL_MAX_DEPTH);
    if (d->threads < 0 || d->threads > IL_MAX_THREADS)
        return il_fail(err, IL_ERR_INVALID,
                       "render: threads %d is out of range (1 to %d; 0 means all cores)", d->threads,
                       IL_MAX_THREADS);
    if ((unsigned)d->sampler > IL_SAMPLER_PCG)
        return il_fail(err, IL_ERR_INVALID, "render: unknown sampler %d", (int)d->sampler);
    if ((unsigned)d->filter > IL_FILTER_GAUSSIAN)
        return il_fail(err, IL_ERR_INVALID, "render: unknown filter %d", (int)d->filter);
    if (d->method == IL_METHOD_IBL) {
        il_ibl_settings unused;
        return il_ibl_settings_resolve(d->ibl, d, &unused, err);
    }
    if (d->method == IL_METHOD_LINESPACE) {
        il_ls_settings unused;
        return il_ls_settings_resolve(d->linespace, d->max_depth, &unused, err);
    }
    if (d->method == IL_METHOD_RSM) {
        il_rsm_settings unused;
        return il_rsm_settings_resolve(d->rsm, d, &unused, err);
    }
    return IL_OK;
}

il_status il_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                    il_render_stats *stats, il_error *err)
{
    if (stats)
        memset(stats, 0, sizeof *stats);
    il_status st = validate(scene, film, desc, err);
    if (st == IL_OK)
        st = il_distrib_check(desc->distrib, desc, "render", err);
    if (st != IL_OK)
        return st;
    switch (desc->method) {
    case IL_METHOD_RADIOSITY:
        return il_rad_render(scene, film, desc, stats, err);
    case IL_METHOD_HR:
        return il_hr_render(scene, film, desc, stats, err);
    case IL_METHOD_PHOTON:
        return il_pm_render(scene, film, desc, stats, err);
    case IL_METHOD_SPPM:
        return il_sppm_render(scene, film, desc, stats, err);
    case IL_METHOD_IBL:
        return il_ibl_render(scene, film, desc, stats, err);
    case IL_METHOD_LINESPACE:
        return il_ls_render(scene, film, desc, stats, err);
    case IL_METHOD_RSM:
        return il_rsm_render(scene, film, desc, stats, err);
    case IL_METHOD_PT:
    default:
        return il_pt_render(scene, film, desc, IL_PT_MIS, stats, err);
    }
}
