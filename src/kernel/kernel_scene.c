/* Packing a scene for kernel/kernel_path.h; see kernel_scene.h. */
#include "kernel/kernel_scene.h"

#include <stdlib.h>
#include <string.h>
#include "core/error.h"
#include "scene/camera.h"
#include "scene/scene.h"
#include "trace/trace.h"

static ilk_vec3 to_k(il_vec3 v) { return ilk_v3(v.x, v.y, v.z); }

il_status il_kscene_build(const il_scene *scene, uint32_t width, uint32_t height, uint32_t max_depth,
                          uint64_t seed, il_kscene *out, il_error *err)
{
    memset(out, 0, sizeof *out);
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID, "kernel scene: the scene is not committed");
    for (uint32_t i = 0; i < scene->num_materials; i++) {
        const il_material *m = &scene->materials[i];
        if (m->type != IL_MATERIAL_DIFFUSE || m->diffuse_texture)
            return il_fail(err, IL_ERR_INVALID, "material '%s': only untextured diffuse materials "
                           "run on the GPU so far (docs/cuda.md)", m->name);
    }
    if (scene->num_user_lights || scene->has_environment)
        return il_fail(err, IL_ERR_INVALID, "only emissive triangles light a GPU render so far "
                       "(no point, spot or directional lights, no environment; docs/cuda.md)");
    il_status st = il_kbvh_build_scene(scene, &out->bvh, err);
    if (st != IL_OK)
        return st;
    out->num_materials = scene->num_materials;
    out->materials = il_calloc(scene->num_materials ? scene->num_materials : 1, sizeof *out->materials, err);
    if (!out->materials) {
        il_kscene_free(out);
        return IL_ERR_MEMORY;
    }
    for (uint32_t i = 0; i < scene->num_materials; i++) {
        const il_material *m = &scene->materials[i];
        out->materials[i].diffuse = to_k(m->diffuse);
        out->materials[i].emission = to_k(m->emission);
        out->materials[i].two_sided = m->two_sided;
    }
    /* Emissive triangles, chosen in proportion to their power
     * Phi = pi A L (one face; twice for two-sided), by luminance. */
    uint32_t n = 0;
    for (uint32_t i = 0; i < out->bvh.num_tris; i++)
        n += !v3_is_zero(scene->materials[out->bvh.tris[i].pad].emission);
    out->lights = il_malloc(sizeof *out->lights * (n ? n : 1), err);
    out->light_cdf = il_malloc(sizeof *out->light_cdf * (n + 1), err);
    if (!out->lights || !out->light_cdf) {
        il_kscene_free(out);
        return IL_ERR_MEMORY;
    }
    double total = 0.0;
    double *power = malloc(sizeof *power * (n ? n : 1));
    if (!power) {
        il_kscene_free(out);
        return il_fail(err, IL_ERR_MEMORY, "out of memory");
    }
    n = 0;
    for (uint32_t i = 0; i < out->bvh.num_tris; i++) {
        const ilk_tri *t = &out->bvh.tris[i];
        const il_material *m = &scene->materials[t->pad];
        if (v3_is_zero(m->emission))
            continue;
        ilk_vec3 c = ilk_cross(t->e1, t->e2);
        double area = 0.5 * sqrt((double)ilk_dot(c, c));
        power[n] = area * il_luminance(m->emission) * (m->two_sided ? 2.0 : 1.0);
        total += power[n];
        out->lights[n++] = i;
    }
    out->num_lights = n;
    double acc = 0.0;
    out->light_cdf[0] = 0.0f;
    for (uint32_t i = 0; i < n; i++) {
        acc += power[i];
        out->light_cdf[i + 1] = total > 0.0 ? (float)(acc / total) : (float)(i + 1) / (float)n;
    }
    if (n)
        out->light_cdf[n] = 1.0f;
    free(power);

    il_camera_desc cd;
    il_scene_get_camera(scene, &cd);
    il_camera cam;
    il_camera_init(&cam, &cd, width, height);
    ilk_scene *v = &out->view;
    v->bvh = il_kbvh_view(&out->bvh);
    v->materials = out->materials;
    v->lights = out->lights;
    v->light_cdf = out->light_cdf;
    v->num_lights = out->num_lights;
    v->epsilon = il_trace_epsilon(scene->tracer);
    v->camera.position = to_k(cam.position);
    v->camera.forward = to_k(cam.forward);
    v->camera.right = to_k(cam.right);
    v->camera.up = to_k(cam.up);
    v->camera.tan_half_x = cam.tan_half_x;
    v->camera.tan_half_y = cam.tan_half_y;
    v->camera.inv_width = cam.inv_width;
    v->camera.inv_height = cam.inv_height;
    v->width = width;
    v->height = height;
    v->max_depth = max_depth ? max_depth : 8;
    v->seed = seed;
    return IL_OK;
}

void il_kscene_free(il_kscene *ks)
{
    il_kbvh_free(&ks->bvh);
    free(ks->materials);
    free(ks->lights);
    free(ks->light_cdf);
    memset(ks, 0, sizeof *ks);
}
