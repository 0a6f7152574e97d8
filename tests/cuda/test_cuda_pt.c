/* The GPU path-tracing megakernel (src/cuda/pt_kernel.cu) on the Cornell
 * box and on the Cornell box with the Stanford dragon against (a) the same
 * kernel compiled by gcc with the same random streams: the same image up to
 * float rounding (nvcc's FMA contraction can
 * send a few paths another way), and (b) the CPU path tracer il_render:
 * the same mean radiance within noise.  Exits 77 (a skip for ctest) without
 * a GPU or driver, as on CI. */
#include <stdlib.h>
#include <string.h>
#include "cuda_test.h"
#include "kernel/kernel_scene.h"
#include "scene/scene.h"

#define W 64
#define H 64
#define SPP 256

/* The GPU image of the scene against the kernel on the CPU and il_render. */
static void compare(il_scene *s)
{
    il_error err = {0};
    float *gpu = calloc(3 * W * H, sizeof *gpu), *cpu = calloc(3 * W * H, sizeof *cpu);
    CHECK_OK(il_cuda_render_pt(s, W, H, SPP, 8, 3, gpu, &err), &err);

    il_kscene ks;
    CHECK_OK(il_kscene_build(s, W, H, 8, 3, &ks, &err), &err);
    for (uint32_t y = 0; y < H; y++)
        for (uint32_t x = 0; x < W; x++) {
            double acc[3] = {0, 0, 0};
            for (uint32_t i = 0; i < SPP; i++) {
                ilk_vec3 L = ilk_path_sample(&ks.view, x, y, i);
                acc[0] += L.x; acc[1] += L.y; acc[2] += L.z;
            }
            for (int c = 0; c < 3; c++)
                cpu[3 * (y * W + x) + c] = (float)(acc[c] / SPP);
        }
    il_kscene_free(&ks);

    cuda_test_compare(s, W, H, gpu, cpu, SPP, 0.03);
    free(gpu);
    free(cpu);
}

int main(void)
{
    if (cuda_test_require_gpu() != 0)
        return 77;
    il_scene *s = load_committed("cornell");
    if (!s)
        return check_report();
    compare(s);
    il_scene_release(s);

    /* The Cornell box with the Stanford dragon (47,806 triangles). */
    s = load_committed(IL_SOURCE_DIR "/bench/scenes/cornell-dragon.json");
    if (s) {
        compare(s);
        il_scene_release(s);
    }
    return check_report();
}
