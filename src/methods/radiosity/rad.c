/* The radiosity method as a whole (see rad.h for the pipeline): il_rad_run
 * solves, il_rad_render solves and renders through the camera. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/radiosity/rad.h"

/* The big arrays of a mesh (its BVH not counted): for peak_bytes. */
static size_t mesh_bytes(const il_patch_mesh *m)
{
    return (size_t)m->num_patches * sizeof(il_patch) +
           (size_t)m->num_surfaces * sizeof(il_patch_surface) +
           (size_t)m->num_vertices * (sizeof(il_vec3) + sizeof(uint32_t)) +
           (size_t)m->num_tris * (6 * sizeof(uint32_t));
}

/* Direct light, form factors, cache and solve on one mesh.  sol is
 * initialised here; on failure it is freed. */
static il_status solve_mesh(const il_scene *scene, const il_patch_mesh *mesh,
                            const il_rad_settings *settings, il_rad_solution *sol,
                            il_radiosity_stats *stats, size_t *peak, il_error *err)
{
    il_status st = il_rad_solution_init(sol, mesh->num_patches, err);
    if (st != IL_OK)
        return st;
    double t0 = omp_get_wtime();
    il_ff *ff = NULL;
    il_ff_cache *cache = NULL;
    st = il_rad_direct(scene, mesh, settings, sol, err);
    stats->seconds_solve += omp_get_wtime() - t0;
    if (st == IL_OK) {
        /* Building the form-factor back-end (hemicube tables) counts as form factors. */
        double t1 = omp_get_wtime();
        st = il_ff_create(mesh, settings, &ff, err);
        stats->seconds_form_factors += omp_get_wtime() - t1;
        if (st == IL_OK)
            stats->form_factors = il_ff_method(ff);
    }
    if (st == IL_OK)
        st = il_ff_cache_create(mesh->num_patches, settings->ff_cache_bytes, &cache, err);
    il_rad_settings own = *settings;
    float *view = NULL;
    if (st == IL_OK)
        st = il_rad_view_weights(scene, mesh, &view, err);
    own.view_weight = view;
    if (st == IL_OK) {
        uint64_t before = stats->peak_bytes;
        stats->peak_bytes = 0;
        st = il_rad_solve(mesh, ff, cache, &own, sol, stats, err);
        size_t total = (size_t)stats->peak_bytes + mesh_bytes(mesh) +
                       3 * (size_t)mesh->num_patches * sizeof(il_vec3) + il_ff_cache_bytes(cache);
        stats->peak_bytes = before;
        if (total > *peak)
            *peak = total;
    }
    free(view);
    if (cache)
        il_ff_cache_release(cache);
    if (ff)
        il_ff_release(ff);
    if (st != IL_OK)
        il_rad_solution_free(sol);
    return st;
}

static il_status run(const il_scene *scene, const il_render_desc *desc,
                     bool (*on_patches)(const il_patch_mesh *, const float *, void *),
                     void *on_patches_user, il_patch_mesh **mesh_out, il_rad_solution *sol_out,
                     il_vec3 **vertex_radiance_out, il_render_stats *stats, il_error *err)
{
    if (mesh_out)
        *mesh_out = NULL;
    if (vertex_radiance_out)
        *vertex_radiance_out = NULL;
    if (sol_out)
        memset(sol_out, 0, sizeof *sol_out);
    il_render_stats local_stats;
    if (!stats)
        stats = &local_stats;
    memset(stats, 0, sizeof *stats);
    il_radiosity_stats *rs = &stats->radiosity;
    if (!scene || !desc)
        return il_fail(err, IL_ERR_INVALID, "radiosity: a scene and render options are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID,
                       "radiosity: the scene is not committed (call il_scene_commit first)");

    double t_start = omp_get_wtime();
    il_rad_settings settings;
    il_status st = il_rad_settings_resolve(scene, desc, &settings, err);
    if (st != IL_OK)
        return st;
    settings.on_patches = on_patches;
    settings.on_patches_user = on_patches_user;

    il_patch_mesh *mesh = NULL;
    il_rad_solution sol;
    memset(&sol, 0, sizeof sol);
    il_vec3 *vr = NULL;
    bool *split = NULL;
    size_t peak = 0;

    double t0 = omp_get_wtime();
    il_patch_sizing sizing = {settings.patch_size, settings.subdivisions};
    st = il_patch_mesh_build(scene, &sizing, &mesh, err);
    rs->seconds_mesh += omp_get_wtime() - t0;
    if (st != IL_OK)
        goto fail;
    st = solve_mesh(scene, mesh, &settings, &sol, rs, &peak, err);
    if (st != IL_OK)
        goto fail;

    if (settings.adaptive_threshold > 0.0f) {
        /* One adaptive pass: split where the solution varies, solve again. */
        split = il_calloc(mesh->num_patches ? mesh->num_patches : 1u, sizeof *split, err);
        if (!split) {
            st = IL_ERR_MEMORY;
            goto fail;
        }
        uint32_t marked = il_rad_mark_split(mesh, &sol, settings.adaptive_threshold, split);
        if (marked > 0) {
            il_patch_mesh *fine = NULL;
            t0 = omp_get_wtime();
            st = il_patch_mesh_refine(scene, mesh, split, &fine, err);
            rs->seconds_mesh += omp_get_wtime() - t0;
            if (st != IL_OK)
                goto fail;
            il_patch_mesh_release(mesh);
            il_rad_solution_free(&sol);
            mesh = fine;
            st = solve_mesh(scene, mesh, &settings, &sol, rs, &peak, err);
            if (st != IL_OK)
                goto fail;
        }
        free(split);
        split = NULL;
    }

    vr = il_malloc((size_t)(mesh->num_vertices ? mesh->num_vertices : 1u) * sizeof *vr, err);
    if (!vr) {
        st = IL_ERR_MEMORY;
        goto fail;
    }
    il_patch_vertex_radiance(mesh, sol.radiance, vr);
    peak += (size_t)mesh->num_vertices * sizeof *vr;

    rs->num_patches = mesh->num_patches;
    rs->num_surfaces = mesh->num_surfaces;
    rs->unshot_fraction = sol.unshot_fraction;
    rs->view_fraction = sol.view_fraction;
    rs->peak_bytes = peak;
    stats->seconds = omp_get_wtime() - t_start;

    if (mesh_out)
        *mesh_out = mesh;
    else
        il_patch_mesh_release(mesh);
    if (sol_out)
        *sol_out = sol;
    else
        il_rad_solution_free(&sol);
    if (vertex_radiance_out)
        *vertex_radiance_out = vr;
    else
        free(vr);
    return IL_OK;

fail:
    free(split);
    free(vr);
    il_rad_solution_free(&sol);
    if (mesh)
        il_patch_mesh_release(mesh);
    return st;
}

il_status il_rad_run(const il_scene *scene, const il_render_desc *desc, il_patch_mesh **mesh_out,
                     il_rad_solution *sol_out, il_vec3 **vertex_radiance_out,
                     il_render_stats *stats, il_error *err)
{
    return run(scene, desc, NULL, NULL, mesh_out, sol_out, vertex_radiance_out, stats, err);
}

il_status il_rad_run_watched(const il_scene *scene, const il_render_desc *desc,
                             bool (*on_patches)(const il_patch_mesh *mesh, const float *radiance,
                                                void *user),
                             void *on_patches_user, il_patch_mesh **mesh_out,
                             il_vec3 **vertex_radiance_out, il_render_stats *stats, il_error *err)
{
    return run(scene, desc, on_patches, on_patches_user, mesh_out, NULL, vertex_radiance_out,
               stats, err);
}

/* il_rad_run without the per-patch radiance: an il_patch_solve_fn. */
static il_status rad_solve(const il_scene *scene, const il_render_desc *desc, il_patch_mesh **mesh_out,
                           il_vec3 **vertex_radiance_out, il_render_stats *stats, il_error *err)
{
    return il_rad_run(scene, desc, mesh_out, NULL, vertex_radiance_out, stats, err);
}

il_status il_rad_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                        il_render_stats *stats, il_error *err)
{
    il_render_stats local;
    if (!stats)
        stats = &local;
    /* Split across processes (desc->distrib) every process solves (its
     * share of the work, exchanged) and renders its share of the camera
     * pass's tiles (camera_pass.c): the films add up to one process's. */
    return il_patch_solve_and_render(scene, film, desc, rad_solve, stats,
                                     &stats->radiosity.seconds_render, err);
}
