/* The GPU photon method (src/cuda/photon_kernel.cu) on the Cornell box
 * against the same shared kernels compiled by gcc (kernel/
 * kernel_photon_map.c): the photon map (records stored, their power, the
 * sorted order and the cell ranges: the same up to the few photons that
 * nvcc's FMA contraction sends another way or into a neighbouring cell),
 * the gathered image (the same up to float rounding), and the image
 * against the CPU path tracer il_render (mean within the density
 * estimate's bias, as tests/unit/test_kernel_photon.c).  Exits 77 (a skip
 * for ctest) without a GPU or driver, as on CI. */
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
    uint64_t same_place = 0, same_cells = 0;
    for (uint32_t i = 0; i < cpu.grid.count && i < gcount; i++) {
        ilk_vec3 d = ilk_sub(gp[i].p, cpu.photons[i].p);
        same_place += ilk_dot(d, d) < 1e-8f;
    }
    for (size_t h = 0; h < cells; h++)
        same_cells += gs[h] == cpu.cell_start[h] && ge[h] == cpu.cell_end[h];
    printf("records: cpu %u, gpu %u; power cpu (%.5f %.5f %.5f) gpu (%.5f %.5f %.5f); %.3f%% of records at the "
           "same place, %.3f%% of cell ranges equal\n", cpu.grid.count, gcount, pc[0], pc[1], pc[2], pg[0], pg[1],
           pg[2], 100.0 * same_place / cpu.grid.count, 100.0 * same_cells / cells);
    CHECK_REL(gcount, cpu.grid.count, 0.005);
    for (int c = 0; c < 3; c++)
        CHECK_REL(pg[c], pc[c], 0.005);
    CHECK(same_place >= cpu.grid.count * 0.95);
    CHECK(same_cells >= cells * 0.95);

    /* The images. */
    float *g = calloc(3 * W * H, sizeof *g), *k = calloc(3 * W * H, sizeof *k);
    il_cuda_photon_stats ps;
    CHECK_OK(il_cuda_render_photon(s, W, H, SPP, 8, 3, PHOTONS, RADIUS, g, &ps, &err), &err);
    printf("gpu: %llu photons traced in %.4f s (%.1f M photons/s), grid built in %.4f s, gather %.4f s\n",
           (unsigned long long)ps.emitted, ps.seconds_trace, 1e-6 * ps.emitted / fmax(ps.seconds_trace, 1e-9),
           ps.seconds_build, ps.seconds_gather);
    il_kphoton_render(&ks, &cpu, RADIUS, SPP, k);

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
