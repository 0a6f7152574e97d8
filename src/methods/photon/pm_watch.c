/* il_photon_desc.on_step during IL_METHOD_PHOTON's set-up (pm.h): progress
 * reports, on the calling thread, and the stop they may ask for. */
#include <omp.h>

#include "methods/photon/pm.h"

bool il_pm_watch_report(il_pm_watch *w, il_photon_phase phase, uint64_t done, uint64_t total)
{
    if (!w || !w->fn)
        return true;
    if (w->stopped)
        return false;
    il_photon_progress p = {.phase = phase, .done = done, .total = total,
                            .seconds = omp_get_wtime() - w->t0};
    if (!w->fn(&p, w->user))
        w->stopped = true;
    return !w->stopped;
}
