/* The compute device of the command line (docs/cuda.md): `illum info
 * --devices` and `illum render --device cpu|cuda`.  Only this file knows
 * whether the program was built with the CUDA backend (IL_HAVE_CUDA). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "cli/cli.h"
#include "core/error.h"
#ifdef IL_HAVE_CUDA
#include "core/vec.h"
#include "cuda/cuda_backend.h"
#include "kernel/kernel_radiosity_scene.h"
#include "methods/patch_mesh.h"
#include "methods/radiosity/rad.h"
#include "scene/scene.h"
#endif

int cli_devices_list(void)
{
    printf("cpu:        always available (the reference backend)\n");
#ifdef IL_HAVE_CUDA
    il_cuda_device devs[16];
    il_cuda_versions v;
    int n = 0;
    char why[256];
    il_error err = {0};
    if (il_cuda_query(devs, 16, &n, &v, why, sizeof why, &err) != IL_OK) {
        cli_error("%s", err.message);
        return cli_exit_for(err.status);
    }
    if (v.driver)
        printf("cuda:       driver supports CUDA %d.%d, illum built with runtime %d.%d\n", v.driver / 1000,
               v.driver % 1000 / 10, v.runtime / 1000, v.runtime % 1000 / 10);
    else
        printf("cuda:       no driver, illum built with runtime %d.%d\n", v.runtime / 1000, v.runtime % 1000 / 10);
    if (n == 0)
        printf("cuda:       no GPU: %s\n", why);
    for (int i = 0; i < n && i < 16; i++)
        printf("cuda:%d:     %s, %.1f GiB, compute capability %d.%d, %d multiprocessors\n", i, devs[i].name,
               (double)devs[i].total_memory / (1024.0 * 1024.0 * 1024.0), devs[i].cc_major, devs[i].cc_minor,
               devs[i].multiprocessors);
#else
    printf("cuda:       not available: illum was built without CUDA (cmake -DIL_CUDA=ON needs nvcc)\n");
#endif
    return IL_EXIT_OK;
}

bool cli_device_from_name(const char *name, bool *cuda)
{
    if (!strcmp(name, "cpu"))
        *cuda = false;
    else if (!strcmp(name, "cuda"))
        *cuda = true;
    else
        return false;
    return true;
}

int cli_device_require_cuda(void)
{
#ifdef IL_HAVE_CUDA
    il_error err = {0};
    if (il_cuda_require_device(&err) != IL_OK) {
        cli_error("%s", err.message);
        return IL_EXIT_RUNTIME;
    }
    return IL_EXIT_OK;
#else
    cli_error("--device cuda: illum was built without CUDA (rebuild with cmake -DIL_CUDA=ON, "
              "which needs nvcc); use --device cpu");
    return IL_EXIT_RUNTIME;
#endif
}

#ifdef IL_HAVE_CUDA
/* il_cuda_run's image_fn: the running image handed on as an il_image. */
static void hand_running_image(const float *rgb, uint32_t width, uint32_t height, uint32_t spp, void *user)
{
    (void)spp;
    const cli_running_image *running = user;
    il_image img = {.width = width, .height = height, .rgb = (float *)rgb};
    running->write(&img, running->user);
}

/* What the progressive GPU renders are told: the time limit, the progress
 * report and the running image. */
static il_cuda_run run_for(const il_render_desc *desc, const cli_running_image *running)
{
    il_cuda_run run = {.time_limit = desc->time_limit, .progress = desc->progress,
                       .progress_user = desc->progress_user};
    if (running && running->every > 0.0) {
        run.image_every = running->every;
        run.image_fn = hand_running_image;
        run.image_user = (void *)running;
    }
    return run;
}

/* --method photon: the shared photon kernels on the GPU with the CPU
 * method's photon count and radius (a fraction of the scene's diagonal,
 * as methods/photon/pm_settings.c resolves it); the grid with a fixed
 * radius and a uniform kernel, read at the camera's first hit for the
 * indirect light; direct light by a shadow ray there. */
static il_status render_photon(const il_scene *scene, const il_render_desc *desc, uint32_t width, uint32_t height,
                               const cli_running_image *running, float *rgb, il_render_stats *rs, il_error *err)
{
    const il_photon_desc *pd = desc->photon;
    if (pd && pd->final_gather)
        return il_fail(err, IL_ERR_INVALID, "--device cuda --method photon: no final gather on the GPU yet "
                       "(docs/cuda.md); use --device cpu");
    uint64_t photons = pd && pd->photons ? pd->photons : 1000000u;
    if (photons > UINT32_MAX)
        return il_fail(err, IL_ERR_INVALID, "--device cuda --method photon: at most %u photons", UINT32_MAX);
    float diagonal = v3_length(v3_sub(scene->bounds_max, scene->bounds_min));
    float radius = (pd && pd->max_radius > 0.0f ? pd->max_radius : 0.02f) * (diagonal > 0.0f ? diagonal : 1.0f);
    il_cuda_photon_stats ps;
    /* A photon of d bounces leaves d + 1 records (pm_settings.c: d is
     * max_depth - 1 by default). */
    uint32_t records = pd && pd->max_photon_depth ? pd->max_photon_depth + 1 : desc->max_depth;
    il_cuda_run run = run_for(desc, running);
    il_status st = il_cuda_render_photon(scene, width, height, desc->spp, records, desc->seed, (uint32_t)photons,
                                         radius, rgb, &ps, &run, err);
    if (st != IL_OK)
        return st;
    rs->spp = run.spp_done;
    rs->rays = run.rays;
    rs->photon.emitted = ps.emitted;
    rs->photon.stored_global = ps.stored;
    rs->photon.passes = 1;
    rs->photon.seconds_trace = ps.seconds_trace;
    rs->photon.seconds_build = ps.seconds_build;
    rs->photon.seconds_render = ps.seconds_gather;
    rs->photon.bytes_per_photon = (uint32_t)sizeof(ilk_photon);
    return IL_OK;
}

/* --method radiosity: meshing and the direct light as the CPU method
 * (methods/radiosity/), the form factors (ray-cast) and the Jacobi
 * gathering on the GPU, then the CPU's camera pass over the per-vertex
 * radiance. */
static il_status render_radiosity(const il_scene *scene, const il_render_desc *desc, uint32_t width,
                                  uint32_t height, il_image *out, il_render_stats *rs, il_error *err)
{
    il_rad_settings settings;
    il_status st = il_rad_settings_resolve(scene, desc, &settings, err);
    if (st != IL_OK)
        return st;
    if (settings.adaptive_threshold > 0.0f)
        return il_fail(err, IL_ERR_INVALID, "--device cuda --method radiosity: no adaptive subdivision on the "
                       "GPU yet (docs/cuda.md); use --device cpu");
    double t0 = cli_now_seconds();
    il_patch_mesh *mesh = NULL;
    il_rad_solution sol;
    memset(&sol, 0, sizeof sol);
    il_krad k;
    memset(&k, 0, sizeof k);
    ilk_vec3 *radiance = NULL;
    il_vec3 *vr = NULL;
    il_film *film = NULL;
    il_patch_sizing sizing = {settings.patch_size, settings.subdivisions};
    il_radiosity_stats *r = &rs->radiosity;
    if ((st = il_patch_mesh_build(scene, &sizing, &mesh, err)) != IL_OK)
        return st;
    r->seconds_mesh = cli_now_seconds() - t0;
    if ((st = il_rad_solution_init(&sol, mesh->num_patches, err)) == IL_OK &&
        (st = il_rad_direct(scene, mesh, &settings, &sol, err)) == IL_OK &&
        (st = il_krad_build(mesh, sol.direct, settings.ray_samples, settings.seed, &k, err)) == IL_OK) {
        size_t np = mesh->num_patches ? mesh->num_patches : 1;
        radiance = il_malloc(sizeof *radiance * np, err);
        vr = il_malloc(sizeof *vr * (mesh->num_vertices ? mesh->num_vertices : 1), err);
        if (!radiance || !vr)
            st = IL_ERR_MEMORY;
    }
    il_cuda_radiosity_stats cs = {0, 0, false};
    uint32_t steps = 0;
    double frac = 0.0;
    if (st == IL_OK)
        st = il_cuda_radiosity_solve(&k, settings.tolerance, settings.max_steps, radiance, &steps, &frac, &cs, err);
    if (st == IL_OK) {
        r->num_patches = mesh->num_patches;
        r->num_surfaces = mesh->num_surfaces;
        r->steps = steps;
        r->unshot_fraction = frac;
        r->stalled = cs.stalled;
        r->form_factors = IL_FF_RAYCAST; /* the GPU's only back-end (docs/cuda.md) */
        r->seconds_form_factors = cs.seconds_form_factors;
        r->seconds_solve = cs.seconds_form_factors + cs.seconds_sweeps;
        r->rows_computed = mesh->num_patches;
        /* ilk_vec3 has il_vec3's layout (kernel/kernel_math.h). */
        for (uint32_t i = 0; i < mesh->num_patches; i++)
            sol.radiance[i] = v3(radiance[i].x, radiance[i].y, radiance[i].z);
        il_patch_vertex_radiance(mesh, sol.radiance, vr);
        double t1 = cli_now_seconds();
        if ((st = il_film_create(width, height, &film, err)) == IL_OK &&
            (st = il_patch_render_film(scene, mesh, vr, film, desc, rs, err)) == IL_OK)
            st = il_film_resolve(film, out, err);
        r->seconds_render = cli_now_seconds() - t1;
    }
    il_film_release(film);
    free(vr);
    free(radiance);
    il_krad_free(&k);
    il_rad_solution_free(&sol);
    il_patch_mesh_release(mesh);
    return st;
}
#endif

il_status cli_device_render_cuda(const il_scene *scene, const il_render_desc *desc, uint32_t width,
                                 uint32_t height, const cli_running_image *running, il_image *out,
                                 il_render_stats *rs, il_error *err)
{
    memset(out, 0, sizeof *out);
    bool supported = desc->method == IL_METHOD_PT || desc->method == IL_METHOD_PHOTON ||
                     desc->method == IL_METHOD_RADIOSITY;
    if (!supported)
        return il_fail(err, IL_ERR_INVALID, "--device cuda renders --method pt, photon or radiosity only so far "
                       "(docs/cuda.md)");
    if (desc->method == IL_METHOD_RADIOSITY && desc->time_limit > 0.0)
        return il_fail(err, IL_ERR_INVALID, "--device cuda --method radiosity renders with --spp, not --time "
                       "(docs/cuda.md)");
#ifdef IL_HAVE_CUDA
    double t0 = cli_now_seconds();
    il_status st;
    if (desc->method == IL_METHOD_RADIOSITY) {
        st = render_radiosity(scene, desc, width, height, out, rs, err);
        rs->seconds = cli_now_seconds() - t0;
        return st;
    }
    float *rgb = il_malloc(sizeof *rgb * 3 * (size_t)width * height, err);
    if (!rgb)
        return IL_ERR_MEMORY;
    if (desc->method == IL_METHOD_PHOTON) {
        st = render_photon(scene, desc, width, height, running, rgb, rs, err);
    } else {
        il_cuda_run run = run_for(desc, running);
        st = il_cuda_render_pt(scene, width, height, desc->spp, desc->max_depth, desc->seed, rgb, &run, err);
        rs->spp = run.spp_done;
        rs->rays = run.rays;
    }
    if (st != IL_OK) {
        free(rgb);
        return st;
    }
    out->width = width;
    out->height = height;
    out->rgb = rgb;
    rs->seconds = cli_now_seconds() - t0;
    return IL_OK;
#else
    (void)scene; (void)width; (void)height; (void)running; (void)rs;
    return il_fail(err, IL_ERR_RUNTIME, "--device cuda: illum was built without CUDA");
#endif
}
