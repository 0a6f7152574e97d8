/* il_rad_direct: the light that point, spot and directional lights and the
 * sky put on each patch, turned into outgoing radiance (the initial unshot
 * radiance of progressive refinement, Cohen et al. 1988, section 3: light
 * sources that are not patches "shoot" first, analytically):
 * direct_i = Le_i + rho_i / pi * E_i, E_i from il_patch_direct_irradiance
 * (methods/patch_direct.c), random numbers keyed by (seed, patch). */
#include "core/error.h"
#include "methods/patch_direct.h"
#include "methods/radiosity/rad.h"

il_status il_rad_direct(const il_scene *scene, const il_patch_mesh *mesh,
                        const il_rad_settings *settings, il_rad_solution *sol, il_error *err)
{
    if (!scene || !mesh || !settings || !sol || sol->num_patches != mesh->num_patches)
        return il_fail(err, IL_ERR_INVALID, "radiosity: direct light needs a mesh and its solution");
    bool delta, sky;
    il_patch_direct_kinds(scene, &delta, &sky);
    uint32_t n = mesh->num_patches;
#pragma omp parallel for schedule(dynamic, 32) num_threads(settings->threads)
    for (uint32_t i = 0; i < n; i++) {
        const il_patch *p = &mesh->patches[i];
        il_vec3 d = p->emission;
        if ((delta || sky) && !v3_is_zero(p->rho)) {
            il_vec3 c[4];
            for (uint32_t k = 0; k < p->num_corners; k++)
                c[k] = mesh->positions[p->v[k]];
            il_vec3 e = il_patch_direct_irradiance(scene, c, p->num_corners, p->normal,
                                                   settings->seed, i, delta, sky);
            d = v3_add(d, v3_scale(v3_mul(p->rho, e), IL_INV_PI));
        }
        sol->direct[i] = d;
    }
    return IL_OK;
}
