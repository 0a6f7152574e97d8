/* The ibl options: defaults and ranges (docs/ibl.md lists them). */
#include <math.h>

#include "core/error.h"
#include "methods/ibl/ibl.h"

il_status il_ibl_settings_resolve(const il_ibl_desc *d, const il_render_desc *rd,
                                  il_ibl_settings *out, il_error *err)
{
    il_ibl_desc z = {0};
    if (!d)
        d = &z;
    if (d->lights > IL_IBL_MAX_LIGHTS)
        return il_fail(err, IL_ERR_INVALID, "ibl: %u lights is out of range (1 to %u)", d->lights,
                       IL_IBL_MAX_LIGHTS);
    if ((unsigned)d->selection > IL_IBL_RANDOM)
        return il_fail(err, IL_ERR_INVALID, "ibl: unknown light selection %d", (int)d->selection);
    if ((unsigned)d->shadows > IL_IBL_SHADOW_NONE)
        return il_fail(err, IL_ERR_INVALID, "ibl: unknown shadow method %d", (int)d->shadows);
    if (d->batch > IL_IBL_MAX_LIGHTS)
        return il_fail(err, IL_ERR_INVALID, "ibl: batch %u is out of range (1 to %u)", d->batch,
                       IL_IBL_MAX_LIGHTS);
    if (d->shadow_map_size > IL_IBL_MAX_MAP)
        return il_fail(err, IL_ERR_INVALID,
                       "ibl: shadow map size %u is out of range (1 to %u texels per side)",
                       d->shadow_map_size, IL_IBL_MAX_MAP);
    if (!(d->shadow_bias >= 0.0f && d->shadow_bias <= 1.0f))
        return il_fail(err, IL_ERR_INVALID,
                       "ibl: shadow bias %g is out of range (0 to 1 of the scene's diagonal)",
                       (double)d->shadow_bias);
    if (d->pcf_taps > IL_IBL_MAX_PCF || (d->pcf_taps != 0 && d->pcf_taps % 2 == 0))
        return il_fail(err, IL_ERR_INVALID,
                       "ibl: pcf taps %u must be odd, 1 to %u (a filter centred on the texel)",
                       d->pcf_taps, IL_IBL_MAX_PCF);
    uint32_t spp = rd && rd->spp ? rd->spp : 1u;
    if (spp > IL_IBL_MAX_SPP)
        return il_fail(err, IL_ERR_INVALID,
                       "ibl: spp %u is out of range (1 to %u camera samples per pixel; every one "
                       "is shaded by every light)",
                       spp, IL_IBL_MAX_SPP);
    out->lights = d->lights ? d->lights : 1024u;
    out->batch = d->batch ? d->batch : 64u;
    if (out->batch > out->lights)
        out->batch = out->lights;
    out->selection = d->selection;
    out->shadows = d->shadows;
    out->shadow_map_size = d->shadow_map_size ? d->shadow_map_size : 512u;
    out->shadow_bias = d->shadow_bias > 0.0f ? d->shadow_bias : 0.001f;
    out->pcf_taps = d->pcf_taps ? d->pcf_taps : 3u;
    out->spp = spp;
    out->max_depth = rd && rd->max_depth ? rd->max_depth : 8u;
    return IL_OK;
}
