/* Device discovery for `illum info --devices` and `--device cuda`: plain
 * CUDA runtime queries, with the two failures a machine without a GPU gives
 * (no driver: cudaErrorInsufficientDriver / cudaErrorNoDevice) reported as
 * "none" rather than as errors. */
#include <stdio.h>
#include <string.h>
#include "cuda/cuda_backend.h"
#include "cuda/cuda_util.h"

static void set_why(char *why, size_t why_size, const char *msg, cudaError_t e)
{
    if (why && why_size)
        snprintf(why, why_size, "%s (%s)", msg, cudaGetErrorName(e));
}

extern "C" il_status il_cuda_query(il_cuda_device *devs, int max, int *count, il_cuda_versions *versions,
                                   char *why, size_t why_size, il_error *err)
{
    *count = 0;
    if (why && why_size)
        why[0] = '\0';
    il_cuda_versions v = {0, 0};
    cudaRuntimeGetVersion(&v.runtime);
    cudaError_t e = cudaDriverGetVersion(&v.driver);
    if (e != cudaSuccess)
        v.driver = 0;
    if (versions)
        *versions = v;
    int n = 0;
    e = cudaGetDeviceCount(&n);
    if (e != cudaSuccess) {
        cudaGetLastError();
        if (v.driver == 0)
            set_why(why, why_size, "no CUDA driver is installed", e);
        else if (e == cudaErrorInsufficientDriver)
            set_why(why, why_size, "the CUDA driver is older than the runtime illum was built with", e);
        else if (e == cudaErrorNoDevice)
            set_why(why, why_size, "no CUDA-capable GPU was found", e);
        else
            set_why(why, why_size, cudaGetErrorString(e), e);
        return IL_OK;
    }
    if (n == 0) {
        set_why(why, why_size, "no CUDA-capable GPU was found", cudaErrorNoDevice);
        return IL_OK;
    }
    for (int i = 0; i < n && i < max; i++) {
        cudaDeviceProp p;
        il_status st = il_cuda_check(cudaGetDeviceProperties(&p, i), "cudaGetDeviceProperties", err);
        if (st != IL_OK)
            return st;
        il_cuda_device *d = &devs[i];
        memset(d, 0, sizeof *d);
        snprintf(d->name, sizeof d->name, "%s", p.name);
        d->total_memory = p.totalGlobalMem;
        d->cc_major = p.major;
        d->cc_minor = p.minor;
        d->multiprocessors = p.multiProcessorCount;
    }
    *count = n;
    return IL_OK;
}

extern "C" il_status il_cuda_require_device(il_error *err)
{
    il_cuda_device dev;
    il_cuda_versions v;
    int n = 0;
    char why[256];
    il_status st = il_cuda_query(&dev, 1, &n, &v, why, sizeof why, err);
    if (st != IL_OK)
        return st;
    if (n == 0)
        return il_fail(err, IL_ERR_RUNTIME, "--device cuda: %s; use --device cpu", why);
    if ((st = il_cuda_check(cudaSetDevice(0), "cudaSetDevice", err)) != IL_OK)
        return st;
    /* A first runtime call that needs a context: fails here, with a clear
     * message, when the binary has no code for this GPU. */
    return il_cuda_check(cudaFree(0), "creating a CUDA context", err);
}
