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

enum { VIEW_RAYS_ACROSS = 64 };

il_status il_rad_view_weights(const il_scene *scene, const il_patch_mesh *mesh, uint32_t width,
                              uint32_t height, float **out, il_error *err)
{
    *out = NULL;
    il_camera_desc d;
    if (!il_scene_get_camera(scene, &d) || mesh->num_patches == 0)
        return IL_OK;
    /* The film's aspect (4:3 when not given) on a grid 64 rays across. */
    double aspect = width && height ? (double)height / width : 0.75;
    uint32_t gw = VIEW_RAYS_ACROSS, gh = (uint32_t)(VIEW_RAYS_ACROSS * aspect + 0.5);
    gh = gh < 1 ? 1 : gh > 4 * VIEW_RAYS_ACROSS ? 4 * VIEW_RAYS_ACROSS : gh;
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
