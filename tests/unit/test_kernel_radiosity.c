/* The shared radiosity kernel (src/kernel/kernel_radiosity.h, compiled here
 * by gcc exactly as nvcc compiles it for src/cuda/radiosity_kernel.cu)
 * against the CPU radiosity solver (il_rad_run, ray-cast form factors,
 * Jacobi gathering) on the Cornell box:
 *  - form-factor rows: the kernel's rays are the CPU's rays, so each row's
 *    hit counts agree but for the few rays the two ray casters (our BVH,
 *    Embree) send to different patches, also when a row is cast in parts
 *    (as the GPU's threads cast it);
 *  - the solution per patch within 0.5% (the bound), with the same
 *    number of sweeps;
 *  - bad input is refused. */
#include <stdlib.h>
#include <string.h>
#include "scene_build.h"
#include "kernel/kernel_radiosity_scene.h"
#include "methods/radiosity/rad.h"
#include "scene/scene.h"

#define SAMPLES 1024
#define SEED 11

int main(void)
{
    il_error err = {0};
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    il_radiosity_desc rdesc = {.subdivisions = 3, .form_factors = IL_FF_RAYCAST, .ray_samples = SAMPLES,
                               .solver = IL_SOLVER_JACOBI, .tolerance = 1e-4f};
    il_render_desc rd = {.method = IL_METHOD_RADIOSITY, .seed = SEED, .radiosity = &rdesc};
    il_patch_mesh *mesh = NULL;
    il_rad_solution sol;
    il_render_stats stats = {0};
    CHECK_OK(il_rad_run(s, &rd, &mesh, &sol, NULL, &stats, &err), &err);
    if (!mesh) {
        il_scene_release(s);
        return check_report();
    }
    uint32_t n = mesh->num_patches;
    il_krad k;
    CHECK_OK(il_krad_build(mesh, sol.direct, SAMPLES, SEED, &k, &err), &err);

    /* Rows: the CPU's sparse row against the kernel's hit list. */
    uint32_t *hits = malloc(sizeof *hits * SAMPLES);
    float *scratch = calloc(n, sizeof *scratch);
    uint32_t *counts = calloc(n, sizeof *counts);
    il_ff_row row = {0, malloc(sizeof(uint32_t) * n), malloc(sizeof(float) * n)};
    /* A row cast in parts (the generator advanced past earlier samples)
     * is the row cast whole. */
    uint32_t *whole = malloc(sizeof *whole * SAMPLES);
    uint32_t parts_differ = 0;
    for (uint32_t i = 0; i < n; i += 97) {
        ilk_rad_row(&k.view, i, whole);
        for (uint32_t first = 0; first < SAMPLES; first += 100)
            ilk_rad_row_part(&k.view, i, first, 100, hits + first);
        parts_differ += memcmp(whole, hits, sizeof *hits * SAMPLES) != 0;
    }
    CHECK(parts_differ == 0);
    free(whole);
    uint64_t rays_differing = 0;
    uint32_t worst_row_rays = 0;
    for (uint32_t i = 0; i < n; i++) {
        ilk_rad_row(&k.view, i, hits);
        for (uint32_t r = 0; r < SAMPLES; r++)
            if (hits[r] != ILK_NO_PATCH)
                counts[hits[r]]++;
        il_ff_ray_row(mesh, SAMPLES, SEED, i, scratch, &row);
        uint32_t diff = 0;
        for (uint32_t e = 0; e < row.count; e++) {
            int cpu = (int)lrintf(row.value[e] * SAMPLES), ker = (int)counts[row.index[e]];
            diff += (uint32_t)abs(cpu - ker);
            counts[row.index[e]] = 0;
        }
        for (uint32_t j = 0; j < n; j++) {
            diff += counts[j];      /* hits the CPU row does not have */
            counts[j] = 0;
        }
        rays_differing += diff;
        if (diff > worst_row_rays)
            worst_row_rays = diff;
    }
    printf("%u patches, %u rays each: %llu of %llu ray tallies differ from the CPU rows (worst row %u)\n", n,
           SAMPLES, (unsigned long long)rays_differing, (unsigned long long)n * SAMPLES, worst_row_rays);
    CHECK(n > 100);
    CHECK(rays_differing <= (uint64_t)n * SAMPLES / 1000);
    CHECK(worst_row_rays <= SAMPLES / 50);

    /* The solution per patch. */
    ilk_vec3 *L = malloc(sizeof *L * n);
    uint32_t steps = 0;
    double frac = 0.0;
    CHECK_OK(il_krad_solve(&k, rdesc.tolerance, 0, L, &steps, &frac, NULL, &err), &err);
    double brightest = 0.0, worst = 0.0;
    uint32_t worst_i = 0;
    for (uint32_t i = 0; i < n; i++)
        brightest = fmax(brightest, il_luminance(sol.radiance[i]));
    for (uint32_t i = 0; i < n; i++) {
        const float *a = &L[i].x, *b = &sol.radiance[i].x;
        for (int c = 0; c < 3; c++) {
            double rel = fabs((double)a[c] - b[c]) / fmax(fabs((double)b[c]), 1e-3 * brightest);
            if (rel > worst) {
                worst = rel;
                worst_i = i;
            }
        }
    }
    printf("solve: kernel %u sweeps (fraction %.3g), cpu %u sweeps (fraction %.3g); worst patch %u differs by "
           "%.4f%%\n", steps, frac, sol.steps, sol.unshot_fraction, worst_i, 100.0 * worst);
    CHECK(steps == sol.steps);
    CHECK(worst < 0.005);
    CHECK(brightest > 0.0);

    /* Bad input. */
    il_krad bad;
    CHECK(il_krad_build(mesh, sol.direct, 0, SEED, &bad, &err) == IL_ERR_INVALID);

    free(L);
    free(hits);
    free(scratch);
    free(counts);
    free(row.index);
    free(row.value);
    il_krad_free(&k);
    il_rad_solution_free(&sol);
    il_patch_mesh_release(mesh);
    il_scene_release(s);
    return check_report();
}
