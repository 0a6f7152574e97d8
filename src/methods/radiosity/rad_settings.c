/* il_rad_settings_resolve: the radiosity options with their defaults
 * (include/illum/illum.h, il_radiosity_desc) and range checks.  Each bad
 * value gives IL_ERR_INVALID with a message naming the option. */
#include <math.h>
#include <omp.h>
#include <string.h>

#include "core/error.h"
#include "methods/distrib.h"
#include "methods/radiosity/rad.h"

/* Limits beyond which an option is certainly a mistake, not a wish. */
#define IL_RAD_MAX_SUBDIVISIONS 10u
#define IL_RAD_MIN_HEMICUBE 8u
#define IL_RAD_MAX_HEMICUBE 4096u
#define IL_RAD_MAX_RAY_SAMPLES (1u << 24)
#define IL_RAD_MAX_CACHE_MB (1u << 20)
#define IL_RAD_MAX_THREADS 4096
/* The automatic patch size aims at about this many patches over the scene. */
#define IL_RAD_AUTO_PATCHES 4000.0

/* Area of the scene's surfaces that get patches (diffuse and Phong). */
static double diffuse_area(const il_scene *scene)
{
    double area = 0.0;
    for (uint32_t m = 0; m < scene->num_meshes; m++) {
        const il_mesh *mesh = &scene->meshes[m];
        il_material_type type = scene->materials[mesh->material].type;
        if (type != IL_MATERIAL_DIFFUSE && type != IL_MATERIAL_PHONG)
            continue;
        for (uint32_t t = 0; t < mesh->num_triangles; t++) {
            const uint32_t *tri = mesh->indices + 3 * (size_t)t;
            il_vec3 a = mesh->positions[tri[0]], b = mesh->positions[tri[1]],
                    c = mesh->positions[tri[2]];
            area += 0.5 * (double)v3_length(v3_cross(v3_sub(b, a), v3_sub(c, a)));
        }
    }
    return area;
}

il_status il_rad_settings_resolve(const il_scene *scene, const il_render_desc *desc,
                                  il_rad_settings *out, il_error *err)
{
    memset(out, 0, sizeof *out);
    if (!scene || !desc)
        return il_fail(err, IL_ERR_INVALID, "radiosity: a scene and render options are required");
    il_radiosity_desc r;
    if (desc->radiosity)
        r = *desc->radiosity;
    else
        memset(&r, 0, sizeof r);

    if (!isfinite(r.patch_size) || r.patch_size < 0.0f)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: patch_size %g is out of range (a positive size in metres; "
                       "0 means automatic)",
                       (double)r.patch_size);
    if (r.subdivisions > IL_RAD_MAX_SUBDIVISIONS)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: subdivisions %u is out of range (0 to %u; each level "
                       "multiplies the patches by 4)",
                       r.subdivisions, IL_RAD_MAX_SUBDIVISIONS);
    if ((unsigned)r.form_factors > IL_FF_RAYCAST)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: unknown form_factors method %d (auto, hemicube or raycast)",
                       (int)r.form_factors);
    if (r.hemicube_resolution != 0 && (r.hemicube_resolution < IL_RAD_MIN_HEMICUBE ||
                                       r.hemicube_resolution > IL_RAD_MAX_HEMICUBE))
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: hemicube_resolution %u is out of range (%u to %u; 0 means 256)",
                       r.hemicube_resolution, IL_RAD_MIN_HEMICUBE, IL_RAD_MAX_HEMICUBE);
    if (r.ray_samples > IL_RAD_MAX_RAY_SAMPLES)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: ray_samples %u is out of range (1 to %u; 0 means 4096)",
                       r.ray_samples, IL_RAD_MAX_RAY_SAMPLES);
    if ((unsigned)r.solver > IL_SOLVER_GAUSS_SEIDEL)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: unknown solver %d (shooting, jacobi or gauss-seidel)",
                       (int)r.solver);
    if (!(r.tolerance >= 0.0f && r.tolerance <= 1.0f))
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: tolerance %g is out of range (above 0, at most 1; 0 means 0.01)",
                       (double)r.tolerance);
    if (r.ff_cache_mb > IL_RAD_MAX_CACHE_MB)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: ff_cache_mb %u is out of range (1 to %u MB; 0 means 1024)",
                       r.ff_cache_mb, IL_RAD_MAX_CACHE_MB);
    if (!isfinite(r.adaptive_threshold) || r.adaptive_threshold < 0.0f)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: adaptive_threshold %g is out of range (0: off, else a "
                       "positive fraction)",
                       (double)r.adaptive_threshold);
    if (desc->threads < 0 || desc->threads > IL_RAD_MAX_THREADS)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: threads %d is out of range (1 to %d; 0 means all cores)",
                       desc->threads, IL_RAD_MAX_THREADS);
    il_status distrib_st = il_distrib_check(desc->distrib, desc, "radiosity", err);
    if (distrib_st != IL_OK)
        return distrib_st;

    out->patch_size = r.patch_size;
    if (out->patch_size == 0.0f) {
        /* About IL_RAD_AUTO_PATCHES square patches over the diffuse area. */
        double area = diffuse_area(scene);
        out->patch_size = area > 0.0 ? (float)sqrt(area / IL_RAD_AUTO_PATCHES) : 1.0f;
        if (!(out->patch_size > 0.0f) || !isfinite(out->patch_size))
            out->patch_size = 1.0f;
    }
    out->subdivisions = r.subdivisions;
    out->form_factors = r.form_factors;
    out->hemicube_resolution = r.hemicube_resolution ? r.hemicube_resolution : 256u;
    out->ray_samples = r.ray_samples ? r.ray_samples : 4096u;
    out->solver = r.solver;
    out->tolerance = r.tolerance > 0.0f ? r.tolerance : 0.01f;
    out->max_steps = r.max_steps;
    out->ff_cache_bytes = (size_t)(r.ff_cache_mb ? r.ff_cache_mb : 1024u) << 20;
    out->adaptive_threshold = r.adaptive_threshold;
    out->on_step = r.on_step;
    out->on_step_user = r.on_step_user;
    out->on_patches = NULL;
    out->on_patches_user = NULL;
    out->seed = desc->seed;
    out->distrib = desc->distrib;
    if (il_distrib_on(desc->distrib)) {
        /* A process that stopped alone would leave the others waiting. */
        out->on_step = NULL;
        out->on_step_user = NULL;
    }
    out->threads = desc->threads > 0 ? desc->threads : omp_get_max_threads();
    if (out->threads < 1)
        out->threads = 1;
    return IL_OK;
}
