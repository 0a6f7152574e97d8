/* What the camera sees of a patch mesh, for the shooting solver's view
 * measure (rad_solve_shoot.c): the share of a coarse grid of camera rays
 * (pixel centres) whose first hit is each patch.
 *
 * Why: the solver's global measure, the unshot power over the initial
 * power, is dominated by whatever holds most of the power.  Under a sky a
 * large ground outside a room holds nearly all of it, so the measure falls
 * below 1% while the light inside the room has made one bounce of its
 * many: a 4 x 5 m room behind a window, with an 80 x 80 m ground, came out
 * 28% darker than the path tracer.  The view measure asks the light that is
 * still unshot to be small next to the light on what the camera sees. */
#include <math.h>
#include <stdlib.h>

#include "core/error.h"
#include "methods/radiosity/rad.h"
#include "scene/camera.h"
#include "trace/trace.h"

/* A 4:3 grid: the solve does not know the film's size (the same solution
 * serves any), and a coarse view is all the measure needs. */
enum { VIEW_RAYS_ACROSS = 64, VIEW_RAYS_DOWN = 48 };

il_status il_rad_view_weights(const il_scene *scene, const il_patch_mesh *mesh, float **out,
                              il_error *err)
{
    *out = NULL;
    il_camera_desc d;
    if (!il_scene_get_camera(scene, &d) || mesh->num_patches == 0)
        return IL_OK;
    const uint32_t gw = VIEW_RAYS_ACROSS, gh = VIEW_RAYS_DOWN;
    il_camera cam;
    il_camera_init(&cam, &d, gw, gh);
    float *w = il_calloc(mesh->num_patches, sizeof *w, err);
    if (!w)
        return IL_ERR_MEMORY;
    uint32_t hits = 0;
    for (uint32_t y = 0; y < gh; y++) {
        for (uint32_t x = 0; x < gw; x++) {
            il_ray ray = {.org = cam.position, .tmin = 0.0f,
                          .dir = il_camera_ray_dir(&cam, (float)x + 0.5f, (float)y + 0.5f),
                          .tmax = INFINITY};
            il_hit hit;
            if (!il_trace_closest(mesh->tracer, &ray, &hit) || mesh->tri_patch[hit.prim] == IL_NO_PATCH)
                continue;
            w[mesh->tri_patch[hit.prim]] += 1.0f;
            hits++;
        }
    }
    if (hits == 0) {
        free(w);
        return IL_OK;
    }
    for (uint32_t i = 0; i < mesh->num_patches; i++)
        w[i] /= (float)hits;
    *out = w;
    return IL_OK;
}
