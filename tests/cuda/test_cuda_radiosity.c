/* The GPU radiosity solve (src/cuda/radiosity_kernel.cu) against the CPU
 * radiosity solver (il_rad_run: ray-cast form factors, Jacobi gathering)
 * and the same shared kernel compiled by gcc (il_krad_solve) on the
 * Cornell box: every patch within 0.5% (the bound), about the same
 * number of sweeps.  Then the solve time of a mesh of about 17,000 patches
 * (printed, not tested).  Then the stall test (methods/radiosity/rad_stall.h)
 * on the GPU: a closed box of albedo 1 stops as stalled after 3 windows,
 * like the kernel on the CPU, and one of albedo 0.999 converges in the same
 * number of sweeps as the kernel on the CPU.  Exits 77 (a skip for ctest) without a GPU or
 * driver, as on CI. */
#include <stdlib.h>
#include <string.h>
#include <time.h>
#include "cuda_test.h"
#include "kernel/kernel_radiosity_scene.h"
#include "methods/radiosity/rad.h"
#include "methods/radiosity/rad_stall.h"
#include "scene/scene.h"
#include "validation/rad_scenes.h"

#define SEED 11

static double worst_patch(const ilk_vec3 *a, const il_vec3 *b, uint32_t n)
{
    double brightest = 0.0, worst = 0.0;
    for (uint32_t i = 0; i < n; i++)
        brightest = fmax(brightest, il_luminance(b[i]));
    for (uint32_t i = 0; i < n; i++) {
        const float *x = &a[i].x, *y = &b[i].x;
        for (int c = 0; c < 3; c++)
            worst = fmax(worst, fabs((double)x[c] - y[c]) / fmax(fabs((double)y[c]), 1e-3 * brightest));
    }
    return worst;
}

static void compare(il_scene *s, uint32_t subdivisions, uint32_t samples, bool check)
{
    il_error err = {0};
    il_radiosity_desc rdesc = {.subdivisions = subdivisions, .form_factors = IL_FF_RAYCAST,
                               .ray_samples = samples, .solver = IL_SOLVER_JACOBI, .tolerance = 1e-4f};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .seed = SEED, .radiosity = &rdesc};
    il_patch_mesh *mesh = NULL;
    il_rad_solution sol;
    il_render_stats stats = {0};
    CHECK_OK(il_rad_run(s, &rd, &mesh, &sol, NULL, &stats, &err), &err);
    if (!mesh)
        return;
    uint32_t n = mesh->num_patches;
    il_krad k;
    CHECK_OK(il_krad_build(mesh, sol.direct, samples, SEED, &k, &err), &err);
    ilk_vec3 *gpu = malloc(sizeof *gpu * n), *cpu = malloc(sizeof *cpu * n);
    uint32_t gsteps = 0, ksteps = 0;
    double gfrac = 0, kfrac = 0;
    il_cuda_radiosity_stats cs = {0, 0, false};
    CHECK_OK(il_cuda_radiosity_solve(&k, rdesc.tolerance, 0, gpu, &gsteps, &gfrac, &cs, &err), &err);
    double worst = worst_patch(gpu, sol.radiance, n);
    printf("%u patches x %u rays: gpu %u sweeps in %.4f s (form factors %.4f s), cpu il_rad_run %u sweeps in "
           "%.3f s; worst patch differs by %.4f%%\n", n, samples, gsteps, cs.seconds_form_factors + cs.seconds_sweeps,
           cs.seconds_form_factors, sol.steps, stats.radiosity.seconds_solve, 100.0 * worst);
    if (check) {
        CHECK_OK(il_krad_solve(&k, rdesc.tolerance, 0, cpu, &ksteps, &kfrac, NULL, &err), &err);
        il_vec3 *kv = malloc(sizeof *kv * n);
        for (uint32_t i = 0; i < n; i++)
            kv[i] = (il_vec3){cpu[i].x, cpu[i].y, cpu[i].z};
        double worst_k = worst_patch(gpu, kv, n);
        printf("against the kernel on the cpu (%u sweeps): worst patch %.4f%%\n", ksteps, 100.0 * worst_k);
        CHECK(worst < 0.005);
        CHECK(worst_k < 0.005);
        CHECK(gsteps + 1 >= sol.steps && gsteps <= sol.steps + 1);
        free(kv);
    }
    free(gpu);
    free(cpu);
    il_krad_free(&k);
    il_rad_solution_free(&sol);
    il_patch_mesh_release(mesh);
}

/* The GPU's Jacobi sweeps and the shared kernel's on the CPU, over the same
 * form factors, on a closed box of albedo rho emitting 1. */
static void test_stall(float rho)
{
    il_error err = {0};
    il_scene *s = new_scene();
    uint32_t m = diffuse_material(s, v3s(rho), v3s(1.0f));
    const uint32_t mat[6] = {m, m, m, m, m, m};
    add_box_room(s, 1.0f, mat);
    CHECK_OK(il_scene_commit(s, &err), &err);
    il_radiosity_desc rdesc = {.subdivisions = 2, .form_factors = IL_FF_RAYCAST, .ray_samples = 64,
                               .solver = IL_SOLVER_JACOBI, .tolerance = 1e-4f};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .seed = 1, .radiosity = &rdesc};
    il_patch_mesh *mesh = NULL;
    il_rad_solution sol;
    il_render_stats stats = {0};
    CHECK_OK(il_rad_run(s, &rd, &mesh, &sol, NULL, &stats, &err), &err);
    if (mesh) {
        uint32_t n = mesh->num_patches, gsteps = 0, ksteps = 0;
        il_krad k;
        CHECK_OK(il_krad_build(mesh, sol.direct, 64, 1, &k, &err), &err);
        ilk_vec3 *gpu = malloc(sizeof *gpu * n), *cpu = malloc(sizeof *cpu * n);
        double gfrac = 0, kfrac = 0;
        bool kstalled = false;
        il_cuda_radiosity_stats cs = {0, 0, false};
        CHECK_OK(il_cuda_radiosity_solve(&k, rdesc.tolerance, 0, gpu, &gsteps, &gfrac, &cs, &err), &err);
        CHECK_OK(il_krad_solve(&k, rdesc.tolerance, 0, cpu, &ksteps, &kfrac, &kstalled, &err), &err);
        printf("closed box rho %.3f: gpu stalled %d after %u sweeps (change %.6f), kernel on the cpu stalled %d "
               "after %u sweeps (change %.6f)\n", (double)rho, (int)cs.stalled, gsteps, gfrac, (int)kstalled,
               ksteps, kfrac);
        CHECK(cs.stalled == kstalled);
        CHECK(cs.stalled == (rho >= 1.0f));
        if (rho >= 1.0f)
            CHECK(gsteps == 3 * IL_RAD_STALL_WINDOW && ksteps == 3 * IL_RAD_STALL_WINDOW);
        else
            CHECK(gsteps + 1 >= ksteps && gsteps <= ksteps + 1 && gfrac < rdesc.tolerance);
        free(gpu);
        free(cpu);
        il_krad_free(&k);
        il_rad_solution_free(&sol);
        il_patch_mesh_release(mesh);
    }
    il_scene_release(s);
}

int main(void)
{
    if (cuda_test_require_gpu() != 0)
        return 77;
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    compare(s, 3, 1024, true);
    compare(s, 5, 256, false);
    il_scene_release(s);
    test_stall(1.0f);
    test_stall(0.999f);
    return check_report();
}
