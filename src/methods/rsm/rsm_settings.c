/* The rsm options: defaults and ranges (docs/rsm.md lists them). */
#include <math.h>

#include "core/error.h"
#include "methods/rsm/rsm.h"

il_status il_rsm_settings_resolve(const il_rsm_desc *d, const il_render_desc *rd,
                                  il_rsm_settings *out, il_error *err)
{
    il_rsm_desc z = {0};
    if (!d)
        d = &z;
    if (d->resolution > IL_RSM_MAX_RESOLUTION)
        return il_fail(err, IL_ERR_INVALID,
                       "rsm: resolution %u is out of range (1 to %u texels per side)",
                       d->resolution, IL_RSM_MAX_RESOLUTION);
    if (d->samples > IL_RSM_MAX_SAMPLES)
        return il_fail(err, IL_ERR_INVALID,
                       "rsm: %u samples is out of range (1 to %u texels per shading point)",
                       d->samples, IL_RSM_MAX_SAMPLES);
    if (!(d->radius >= 0.0f && d->radius <= IL_RSM_MAX_RADIUS))
        return il_fail(err, IL_ERR_INVALID,
                       "rsm: radius %g is out of range (0 to %g of the map's side)",
                       (double)d->radius, (double)IL_RSM_MAX_RADIUS);
    if (d->maps > IL_RSM_MAX_MAPS)
        return il_fail(err, IL_ERR_INVALID,
                       "rsm: %u maps per shading point is out of range (1 to %u)", d->maps,
                       IL_RSM_MAX_MAPS);
    out->resolution = d->resolution ? d->resolution : 512u;
    out->samples = d->samples ? d->samples : 400u;
    out->radius = d->radius > 0.0f ? d->radius : 1.5f;
    out->all_texels = d->all_texels;
    out->maps = d->all_maps ? 0u : d->maps ? d->maps : IL_RSM_DEFAULT_MAPS;
    out->shadow_test = d->shadow_test;
    out->max_depth = rd && rd->max_depth ? rd->max_depth : 8u;
    return IL_OK;
}
