/* The photon-mapping options: defaults, ranges, radii in scene units (fractions
 * of the size of what the camera sees, methods/view_size.h). */
#include <math.h>
#include <string.h>

#include "core/error.h"
#include "methods/photon/pm.h"
#include "methods/portal_light.h"
#include "methods/view_size.h"

#define PM_MAX_PHOTONS 10000000000ull /* 10^10: 200 GB of photons, surely a typo beyond */
#define PM_MAX_K 100000u
#define PM_MAX_GATHER 65536u
#define PM_MAX_DEPTH 1024u

il_status il_pm_settings_resolve(const il_scene *scene, const il_photon_desc *d, uint32_t max_depth,
                                 bool sppm, il_pm_settings *out, il_error *err)
{
    il_photon_desc z = {0};
    if (!d)
        d = &z;
    if (d->photons > PM_MAX_PHOTONS)
        return il_fail(err, IL_ERR_INVALID, "photon: %llu photons is out of range (1 to 10^10)",
                       (unsigned long long)d->photons);
    if (d->k > PM_MAX_K)
        return il_fail(err, IL_ERR_INVALID, "photon: k %u is out of range (1 to %u)", d->k, PM_MAX_K);
    if (!(d->max_radius >= 0.0f && d->max_radius <= 1.0f))
        return il_fail(err, IL_ERR_INVALID,
                       "photon: radius %g is out of range (0 to 1 of the scene's size)",
                       (double)d->max_radius);
    if ((unsigned)d->lookup > IL_PHOTON_GRID)
        return il_fail(err, IL_ERR_INVALID, "photon: unknown lookup %d", (int)d->lookup);
    if ((unsigned)d->filter > IL_PHOTON_EPANECHNIKOV)
        return il_fail(err, IL_ERR_INVALID, "photon: unknown filter %d", (int)d->filter);
    if (d->final_gather > PM_MAX_GATHER)
        return il_fail(err, IL_ERR_INVALID, "photon: final gather %u is out of range (0 to %u)",
                       d->final_gather, PM_MAX_GATHER);
    if (!(d->alpha >= 0.0f && d->alpha < 1.0f))
        return il_fail(err, IL_ERR_INVALID, "sppm: alpha %g is out of range (0 to 1, exclusive)",
                       (double)d->alpha);
    if (!(d->initial_radius >= 0.0f && d->initial_radius <= 1.0f))
        return il_fail(err, IL_ERR_INVALID,
                       "sppm: initial radius %g is out of range (0 to 1 of the scene's size)",
                       (double)d->initial_radius);
    if (d->max_photon_depth > PM_MAX_DEPTH)
        return il_fail(err, IL_ERR_INVALID, "photon: max photon depth %u is out of range (1 to %u)",
                       d->max_photon_depth, PM_MAX_DEPTH);

    float diagonal = il_view_size(scene);
    out->size = diagonal;
    out->portal_light = !d->no_portal_light && il_portal_light_wanted(scene);
    out->photons = d->photons ? d->photons : (sppm ? 250000u : 1000000u);
    out->lookup.lookup = d->lookup;
    out->lookup.k = d->k ? d->k : 100u;
    out->lookup.radius = (d->max_radius > 0.0f ? d->max_radius : 0.02f) * diagonal;
    out->lookup.filter = d->filter;
    out->final_gather = d->final_gather;
    out->alpha = d->alpha > 0.0f ? d->alpha : 0.7f;
    out->initial_radius = (d->initial_radius > 0.0f ? d->initial_radius : 0.01f) * diagonal;
    /* A camera path's diffuse vertex plus the photon's bounces make a path
     * of max_depth scattering events, as the path tracer counts them. */
    uint32_t depth = max_depth ? max_depth : 8u;
    out->max_photon_depth = d->max_photon_depth ? d->max_photon_depth : depth - 1u;
    return IL_OK;
}
