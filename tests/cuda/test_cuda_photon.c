/* The GPU photon method (src/cuda/photon_kernel.cu) on the Cornell box
 * against the same shared kernels compiled by gcc (kernel/
 * kernel_photon_map.c): the photon map (records stored, their power, the
 * same photons at the same places, cells holding their own records), the
 * gathered image (the same up to float rounding), and the image against
 * the CPU path tracer il_render (mean within the density estimate's bias,
 * as tests/unit/test_kernel_photon.c).  Exits 77 (a skip for ctest)
 * without a GPU or driver, as on CI.
 *
 * The maps are compared photon by photon, not entry by entry: the GPU's
 * sinf/cosf (within 2 ulp of glibc's) move photons by rounding steps, and
 * on a wall that lies on a cell boundary (the floor y = 0, the wall
 * x = 0) those steps decide the cell; a photon in another cell moves every
 * sorted entry between the two cells' hashes.  Measured on an H200: the
 * same 697,018 records, 0.5% at the same index, 62% of the used cells with
 * as many photons as the CPU's. */
#include <stdlib.h>
#include <string.h>
#include "cuda_test.h"
#include "kernel/kernel_photon_map.h"
#include "scene/scene.h"

#define W 64
#define H 64
#define SPP 16
#define PHOTONS 400000u
#define RADIUS 0.02f

int main(void)
{
    if (cuda_test_require_gpu() != 0)
        return 77;
    il_error err = {0};
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    il_kscene ks;
    CHECK_OK(il_kscene_build(s, W, H, 8, 3, &ks, &err), &err);

    /* The maps. */
    il_kphoton_map cpu;
    CHECK_OK(il_kphoton_map_build(&ks, PHOTONS, RADIUS, &cpu, &err), &err);
    size_t cells = (size_t)cpu.grid.hash_mask + 1;
    ilk_photon *gp = malloc(sizeof *gp * cpu.num_slots);
    uint32_t *gs = malloc(sizeof *gs * cells), *ge = malloc(sizeof *ge * cells), gcount = 0;
    CHECK_OK(il_cuda_photon_map(&ks, PHOTONS, RADIUS, gp, gs, ge, &gcount, &err), &err);
    double pc[3] = {0, 0, 0}, pg[3] = {0, 0, 0};
    for (uint32_t i = 0; i < cpu.grid.count; i++) {
        pc[0] += cpu.photons[i].power.x; pc[1] += cpu.photons[i].power.y; pc[2] += cpu.photons[i].power.z;
    }
    for (uint32_t i = 0; i < gcount; i++) {
        pg[0] += gp[i].power.x; pg[1] += gp[i].power.y; pg[2] += gp[i].power.z;
    }
    /* The same photons: each GPU record has a CPU record with its bounce
     * count and power within 1e-4 m (the CPU map's own range query). */
    uint64_t same_place = 0, in_cells = 0, cells_ok = 0, cells_used = 0;
    for (uint32_t i = 0; i < gcount; i++) {
        ilk_grid_query q = ilk_grid_query_begin(&cpu.grid, gp[i].p, 1e-4f);
        uint32_t j;
        bool found = false;
        while (!found && ilk_grid_next(&cpu.grid, &q, &j)) {
            const ilk_photon *c = &cpu.photons[j];
            ilk_vec3 d = ilk_sub(c->power, gp[i].power);
            found = c->bounces == gp[i].bounces && ilk_dot(d, d) <= 1e-8f * ilk_dot(c->power, c->power);
        }
        same_place += found;
    }
    /* The GPU's grid over its own records: each used cell's range holds
     * records of that cell's hash only, and the ranges cover the records. */
    for (size_t h = 0; h < cells; h++) {
        if (ge[h] <= gs[h])
            continue;
        cells_used++;
        bool ok = ge[h] <= gcount;
        for (uint32_t k = gs[h]; ok && k < ge[h]; k++)
            ok = ilk_grid_key(&gp[k], cpu.grid.inv_cell, cpu.grid.hash_mask) == h;
        cells_ok += ok;
        in_cells += ge[h] - gs[h];
    }
    printf("records: cpu %u, gpu %u; power cpu (%.5f %.5f %.5f) gpu (%.5f %.5f %.5f); %.3f%% of the gpu's records "
           "found in the cpu's map; %llu of %llu cells used hold only their own records\n", cpu.grid.count, gcount,
           pc[0], pc[1], pc[2], pg[0], pg[1], pg[2], 100.0 * same_place / (gcount ? gcount : 1),
           (unsigned long long)cells_ok, (unsigned long long)cells_used);
    CHECK_REL(gcount, cpu.grid.count, 0.005);
    for (int c = 0; c < 3; c++)
        CHECK_REL(pg[c], pc[c], 0.005);
    CHECK(same_place >= gcount * 0.99);
    CHECK(cells_used > 0 && cells_ok == cells_used && in_cells == gcount);

    /* The images. */
    float *g = calloc(3 * W * H, sizeof *g), *k = calloc(3 * W * H, sizeof *k);
    il_cuda_photon_stats ps;
    il_cuda_run run = {0};
    CHECK_OK(il_cuda_render_photon(s, W, H, SPP, 8, 3, PHOTONS, RADIUS, g, &ps, &run, &err), &err);
    CHECK(run.spp_done == SPP);
    printf("gpu: %llu photons traced in %.4f s (%.1f M photons/s), grid built in %.4f s, gather %.4f s\n",
           (unsigned long long)ps.emitted, ps.seconds_trace, 1e-6 * ps.emitted / fmax(ps.seconds_trace, 1e-9),
           ps.seconds_build, ps.seconds_gather);
    uint64_t cpu_rays = il_kphoton_render(&ks, &cpu, RADIUS, SPP, k);
    /* A camera ray a sample, and a shadow ray where its light sample can
     * give light: the same count on both. */
    printf("rays: gpu %llu, kernel on cpu %llu\n", (unsigned long long)run.rays, (unsigned long long)cpu_rays);
    CHECK(run.rays == cpu_rays && cpu_rays > (uint64_t)W * H * SPP && cpu_rays <= 2ull * W * H * SPP);

    cuda_test_compare(s, W, H, g, k, 256, 0.05);
    free(g);
    free(k);
    free(gp);
    free(gs);
    free(ge);
    il_kphoton_map_free(&cpu);
    il_kscene_free(&ks);
    il_scene_release(s);
    return check_report();
}
