/* The hierarchical radiosity method as a whole (see hr.h for the
 * pipeline): il_hr_run solves and gives per-vertex radiance on the leaves'
 * patch mesh, il_hr_render renders it through the camera. */
#include <omp.h>
#include <stdlib.h>
#include <string.h>

#include "core/error.h"
#include "methods/hr/hr.h"

/* One patch per input polygon: a patch size beyond any scene gives every
 * quad and triangle a 1 x 1 grid (patch_mesh_subdivide.c). */
il_status il_hr_root_mesh(const il_scene *scene, il_patch_mesh **out, il_error *err)
{
    const il_patch_sizing one = {.patch_size = 1e30f, .subdivisions = 0};
    return il_patch_mesh_build(scene, &one, out, err);
}

/* il_hr_run_watched's hook: the leaves' mesh of the solve so far. */
typedef struct watch {
    bool (*on_patches)(const il_patch_mesh *mesh, const float *radiance, void *user);
    void *user;
} watch;

static bool on_iteration(const il_hr_solver *s, void *user)
{
    const watch *w = user;
    il_patch_mesh *mesh = NULL;
    il_vec3 *patch_rad = NULL;
    il_error err = {0};
    if (il_hr_output_mesh(s, &mesh, &patch_rad, &err) != IL_OK)
        return true;          /* no look this time; the solve goes on */
    uint32_t n = mesh->num_patches;
    float *rad = malloc((size_t)(n ? n : 1u) * 3 * sizeof *rad);
    bool go = true;
    if (rad) {
        for (uint32_t i = 0; i < n; i++) {
            rad[3 * (size_t)i + 0] = patch_rad[i].x;
            rad[3 * (size_t)i + 1] = patch_rad[i].y;
            rad[3 * (size_t)i + 2] = patch_rad[i].z;
        }
        go = w->on_patches(mesh, rad, w->user);
    }
    free(rad);
    free(patch_rad);
    if (mesh != s->mesh)
        il_patch_mesh_release(mesh);
    return go;
}

static il_status run(const il_scene *scene, const il_render_desc *desc, const watch *w,
                     il_patch_mesh **mesh_out, il_vec3 **vertex_radiance_out,
                     il_render_stats *stats, il_error *err)
{
    if (mesh_out)
        *mesh_out = NULL;
    if (vertex_radiance_out)
        *vertex_radiance_out = NULL;
    il_render_stats local;
    if (!stats)
        stats = &local;
    memset(stats, 0, sizeof *stats);
    if (!scene || !desc)
        return il_fail(err, IL_ERR_INVALID, "hr: a scene and render options are required");
    if (!scene->committed)
        return il_fail(err, IL_ERR_INVALID,
                       "hr: the scene is not committed (call il_scene_commit first)");
    double t_start = omp_get_wtime();
    il_hr_settings set;
    il_status st = il_hr_settings_resolve(desc, &set, err);
    if (st != IL_OK)
        return st;
    if (w && w->on_patches) {
        set.on_iteration = on_iteration;
        set.on_iteration_user = (void *)w;
    }

    il_patch_mesh *roots = NULL, *mesh = NULL;
    il_vec3 *patch_rad = NULL, *vr = NULL;
    il_hr_solver solver;
    memset(&solver, 0, sizeof solver);
    double t0 = omp_get_wtime();
    st = il_hr_root_mesh(scene, &roots, err);
    double t_mesh = omp_get_wtime() - t0;
    if (st == IL_OK)
        st = il_hr_solve(scene, roots, &set, &solver, err);
    if (st != IL_OK) {
        il_patch_mesh_release(roots);
        return st;
    }
    stats->hr = solver.stats;
    stats->hr.seconds_setup += t_mesh;

    t0 = omp_get_wtime();
    st = il_hr_output_mesh(&solver, &mesh, &patch_rad, err);
    il_hr_solver_free(&solver);
    if (st == IL_OK) {
        vr = il_malloc((size_t)(mesh->num_vertices ? mesh->num_vertices : 1u) * sizeof *vr, err);
        if (!vr)
            st = IL_ERR_MEMORY;
        else
            il_patch_vertex_radiance(mesh, patch_rad, vr);
    }
    free(patch_rad);
    if (mesh != roots)
        il_patch_mesh_release(roots);
    stats->hr.seconds_average = omp_get_wtime() - t0;
    stats->seconds = omp_get_wtime() - t_start;
    if (st != IL_OK) {
        il_patch_mesh_release(mesh);
        free(vr);
        return st;
    }
    if (mesh_out)
        *mesh_out = mesh;
    else
        il_patch_mesh_release(mesh);
    if (vertex_radiance_out)
        *vertex_radiance_out = vr;
    else
        free(vr);
    return IL_OK;
}

il_status il_hr_run(const il_scene *scene, const il_render_desc *desc, il_patch_mesh **mesh_out,
                    il_vec3 **vertex_radiance_out, il_render_stats *stats, il_error *err)
{
    return run(scene, desc, NULL, mesh_out, vertex_radiance_out, stats, err);
}

il_status il_hr_run_watched(const il_scene *scene, const il_render_desc *desc,
                            bool (*on_patches)(const il_patch_mesh *mesh, const float *radiance,
                                               void *user),
                            void *on_patches_user, il_patch_mesh **mesh_out,
                            il_vec3 **vertex_radiance_out, il_render_stats *stats, il_error *err)
{
    watch w = {on_patches, on_patches_user};
    return run(scene, desc, &w, mesh_out, vertex_radiance_out, stats, err);
}

il_status il_hr_render(const il_scene *scene, il_film *film, const il_render_desc *desc,
                       il_render_stats *stats, il_error *err)
{
    il_render_stats local;
    if (!stats)
        stats = &local;
    /* Split across processes (desc->distrib) every process solves (its
     * share of the work, exchanged) and renders its share of the camera
     * pass's tiles (camera_pass.c): the films add up to one process's. */
    return il_patch_solve_and_render(scene, film, desc, il_hr_run, stats, &stats->hr.seconds_render,
                                     err);
}
