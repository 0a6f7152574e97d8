/* il_rad_solution: the per-patch arrays of a solve. */
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/radiosity/rad.h"

il_status il_rad_solution_init(il_rad_solution *sol, uint32_t num_patches, il_error *err)
{
    memset(sol, 0, sizeof *sol);
    size_t n = num_patches ? num_patches : 1u;
    sol->radiance = il_calloc(n, sizeof(il_vec3), err);
    sol->unshot = il_calloc(n, sizeof(il_vec3), err);
    sol->direct = il_calloc(n, sizeof(il_vec3), err);
    if (!sol->radiance || !sol->unshot || !sol->direct) {
        il_rad_solution_free(sol);
        return il_fail(err, IL_ERR_MEMORY, "radiosity: out of memory for %u patches", num_patches);
    }
    sol->num_patches = num_patches;
    return IL_OK;
}

void il_rad_solution_free(il_rad_solution *sol)
{
    if (!sol)
        return;
    free(sol->radiance);
    free(sol->unshot);
    free(sol->direct);
    memset(sol, 0, sizeof *sol);
}
