/* What every GPU test shares: the skip without a GPU, scene loading
 * (scene_build.h), and the comparison of a GPU image with the same kernel
 * run by gcc and with the CPU path tracer. */
#ifndef IL_TEST_CUDA_TEST_H
#define IL_TEST_CUDA_TEST_H

#include <math.h>
#include <stdio.h>
#include "scene_build.h"
#include "cuda/cuda_backend.h"
#include "scene/scene.h"

/* 0 with a GPU (its name printed), else 77: a skip for ctest, as on CI. */
static inline int cuda_test_require_gpu(void)
{
    il_cuda_device dev;
    il_cuda_versions v;
    int count = 0;
    char why[256];
    il_error err = {0};
    if (il_cuda_query(&dev, 1, &count, &v, why, sizeof why, &err) != IL_OK || count == 0) {
        printf("SKIP: no GPU: %s\n", count == 0 ? why : err.message);
        return 77;
    }
    printf("GPU: %s, compute capability %d.%d\n", dev.name, dev.cc_major, dev.cc_minor);
    return 0;
}

/* Checks a w*h RGB GPU image against the same kernel on the CPU (means
 * within 1%, at most 5% of values off by more than 2%) and its mean
 * against il_render's path tracer at `pt_spp` (within pt_tolerance). */
static inline void cuda_test_compare(const il_scene *s, uint32_t w, uint32_t h, const float *gpu,
                                     const float *cpu, uint32_t pt_spp, double pt_tolerance)
{
    il_error err = {0};
    il_film *film = NULL;
    CHECK_OK(il_film_create(w, h, &film, &err), &err);
    il_render_desc rd = {.method = IL_METHOD_PT, .spp = pt_spp, .max_depth = 8, .seed = 9};
    CHECK_OK(il_render(s, film, &rd, NULL, &err), &err);
    il_image img = {0};
    CHECK_OK(il_film_resolve(film, &img, &err), &err);
    double mg[3] = {0, 0, 0}, mk[3] = {0, 0, 0}, mr[3] = {0, 0, 0};
    uint64_t n = (uint64_t)w * h, off = 0;
    for (uint64_t i = 0; i < n; i++)
        for (int c = 0; c < 3; c++) {
            float a = gpu[3 * i + c], b = cpu[3 * i + c];
            mg[c] += a / n;
            mk[c] += b / n;
            mr[c] += (img.rgb ? img.rgb[3 * i + c] : 0.0f) / n;
            if (fabsf(a - b) > 0.02f * fabsf(b) + 1e-4f)
                off++;
        }
    printf("mean gpu (%.5f %.5f %.5f) kernel on cpu (%.5f %.5f %.5f) il_render pt (%.5f %.5f %.5f); "
           "%llu of %llu pixel values differ from the cpu kernel by more than 2%%\n",
           mg[0], mg[1], mg[2], mk[0], mk[1], mk[2], mr[0], mr[1], mr[2], (unsigned long long)off,
           (unsigned long long)(3 * n));
    for (int c = 0; c < 3; c++) {
        CHECK_REL(mg[c], mk[c], 0.01);
        CHECK_REL(mg[c], mr[c], pt_tolerance);
    }
    CHECK(off <= 3 * n / 20);
    il_image_free(&img);
    il_film_release(film);
}

#endif
