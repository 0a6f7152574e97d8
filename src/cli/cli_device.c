/* The compute device of the command line (docs/cuda.md): `illum info
 * --devices` and `illum render --device cpu|cuda`.  Only this file knows
 * whether the program was built with the CUDA backend (IL_HAVE_CUDA). */
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "cli/cli.h"
#include "core/error.h"
#ifdef IL_HAVE_CUDA
#include "cuda/cuda_backend.h"
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

il_status cli_device_render_cuda(const il_scene *scene, const il_render_desc *desc, uint32_t width,
                                 uint32_t height, il_image *out, il_render_stats *rs, il_error *err)
{
    memset(out, 0, sizeof *out);
    if (desc->method != IL_METHOD_PT || desc->time_limit > 0.0)
        return il_fail(err, IL_ERR_INVALID, "--device cuda renders --method pt with --spp only so far "
                       "(docs/cuda.md)");
#ifdef IL_HAVE_CUDA
    uint32_t spp = desc->spp ? desc->spp : 16;
    float *rgb = il_malloc(sizeof *rgb * 3 * (size_t)width * height, err);
    if (!rgb)
        return IL_ERR_MEMORY;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    il_status st = il_cuda_render_pt(scene, width, height, spp, desc->max_depth, desc->seed, rgb, err);
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (st != IL_OK) {
        free(rgb);
        return st;
    }
    out->width = width;
    out->height = height;
    out->rgb = rgb;
    rs->spp = spp;
    rs->seconds = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    return IL_OK;
#else
    (void)scene; (void)width; (void)height; (void)rs;
    return il_fail(err, IL_ERR_RUNTIME, "--device cuda: illum was built without CUDA");
#endif
}
