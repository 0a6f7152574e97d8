/* The path tracer's entry point: the wavefront camera pass
 * (pt_wavefront.c), which gives what the shared camera pass (camera_pass.c)
 * with il_pt_radiance as the per-sample estimate gives, bit for bit. */
#include <string.h>

#include "core/error.h"
#include "methods/camera_pass.h"
#include "methods/pt/pt.h"

il_status il_pt_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_pt_strategy strategy, il_render_stats *stats, il_error *err)
{
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (!scene || !film || !desc)
        return il_fail(err, IL_ERR_INVALID, "render: scene, film and options are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "render: the scene is not committed (call il_scene_commit)");

    uint32_t max_depth = desc->max_depth ? desc->max_depth : 8;
    il_camera_pass_result r;
    il_status st = il_pt_wavefront_pass(scene, film, desc, max_depth, strategy, &r, err);
    if (st != IL_OK)
        return st;
    if (stats) {
        stats->spp = r.spp;
        stats->rays = r.rays;
        stats->seconds = r.seconds;
        stats->nonfinite_samples = r.nonfinite_samples;
    }
    return IL_OK;
}
