/* The Linespace options: defaults and ranges (docs/linespace.md). */
#include <math.h>

#include "core/error.h"
#include "methods/linespace/ls.h"

#define LS_MAX_RAYS 10000000000ull /* 10^10 */
#define LS_MAX_DEPTH 1024u

il_status il_ls_settings_resolve(const il_linespace_desc *d, uint32_t max_depth, il_ls_settings *out,
                                 il_error *err)
{
    il_linespace_desc z = {0};
    if (!d)
        d = &z;
    if (d->grid > IL_LS_MAX_GRID)
        return il_fail(err, IL_ERR_INVALID, "linespace: grid %u is out of range (1 to %u)", d->grid,
                       IL_LS_MAX_GRID);
    if (d->n > IL_LS_MAX_N)
        return il_fail(err, IL_ERR_INVALID, "linespace: N %u is out of range (1 to %u)", d->n,
                       IL_LS_MAX_N);
    if (d->inject_rays > LS_MAX_RAYS)
        return il_fail(err, IL_ERR_INVALID, "linespace: %llu inject rays is out of range (1 to 10^10)",
                       (unsigned long long)d->inject_rays);
    if (d->inject_depth > LS_MAX_DEPTH)
        return il_fail(err, IL_ERR_INVALID, "linespace: inject depth %u is out of range (1 to %u)",
                       d->inject_depth, LS_MAX_DEPTH);
    if (!(d->blur >= 0.0f && d->blur <= 4.0f))
        return il_fail(err, IL_ERR_INVALID,
                       "linespace: blur %g is out of range (0 to 4 of the voxel's smallest side)",
                       (double)d->blur);
    if (d->coarse_below > 255u)
        return il_fail(err, IL_ERR_INVALID, "linespace: coarse-below %u is out of range (1 to 255)",
                       d->coarse_below);
    if (!(d->glossy_n1 >= 0.0f && d->glossy_n1 <= 1e6f) || !(d->glossy_n2 >= 0.0f && d->glossy_n2 <= 1e6f))
        return il_fail(err, IL_ERR_INVALID, "linespace: glossy thresholds must be in 0 to 10^6");
    out->grid = d->grid ? d->grid : 8u;
    out->n = d->n ? d->n : 4u;
    out->inject_rays = d->inject_rays ? d->inject_rays : 1000000u;
    out->on_step = d->on_step;
    out->on_step_user = d->on_step_user;
    out->max_depth = max_depth ? max_depth : 8u;
    /* A light path's segment k has scattered k times; read at a camera
     * vertex it scatters once more, or twice when the first bounce is
     * traced (the path tracer's max_depth counts scattering events). */
    out->trace_first_bounce = d->trace_first_bounce;
    uint32_t camera_bounces = out->trace_first_bounce ? 2u : 1u;
    out->inject_depth = d->inject_depth ? d->inject_depth
                                        : (out->max_depth > camera_bounces ? out->max_depth - camera_bounces : 0);
    out->blur = d->blur;
    out->occlusion_test = !d->no_occlusion_test;
    out->fallback = !d->no_fallback;
    out->fallback_empty = out->fallback && d->fallback_empty;
    out->solid_angle = !d->no_solid_angle;
    out->coarse = d->coarse;
    out->coarse_below = d->coarse_below ? d->coarse_below : 32u;
    out->portal_light = !d->no_portal_light;
    out->n1 = d->glossy_n1 > 0.0f ? d->glossy_n1 : 10.0f;
    out->n2 = d->glossy_n2 > 0.0f ? d->glossy_n2 : 100.0f;
    if (out->n2 < out->n1)
        return il_fail(err, IL_ERR_INVALID, "linespace: glossy n2 (%g) is below n1 (%g)",
                       (double)out->n2, (double)out->n1);
    return IL_OK;
}
