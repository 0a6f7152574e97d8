/* The path tracer's entry point: the shared camera pass (camera_pass.c)
 * with il_pt_radiance as the per-sample estimate. */
#include <string.h>

#include "core/error.h"
#include "methods/camera_pass.h"
#include "methods/pt/pt.h"

typedef struct pt_method {
    const il_scene *scene;
    uint32_t max_depth;
    il_pt_strategy strategy;
} pt_method;

static il_vec3 pt_camera_radiance(const void *method, il_vec3 org, il_vec3 dir, il_sampler *smp,
                                  uint64_t *rays)
{
    const pt_method *m = method;
    return il_pt_radiance(m->scene, org, dir, smp, m->max_depth, m->strategy, rays);
}

il_status il_pt_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_pt_strategy strategy, il_render_stats *stats, il_error *err)
{
    if (stats)
        memset(stats, 0, sizeof *stats);
    if (!scene || !film || !desc)
        return il_fail(err, IL_ERR_INVALID, "render: scene, film and options are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "render: the scene is not committed (call il_scene_commit)");

    pt_method m = {.scene = scene, .max_depth = desc->max_depth ? desc->max_depth : 8,
                   .strategy = strategy};
    il_camera_pass_result r;
    il_camera_pass(scene, film, desc, pt_camera_radiance, &m, &r);
    if (stats) {
        stats->spp = r.spp;
        stats->rays = r.rays;
        stats->seconds = r.seconds;
        stats->nonfinite_samples = r.nonfinite_samples;
    }
    return IL_OK;
}
