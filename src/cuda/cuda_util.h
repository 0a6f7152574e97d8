/* Error handling shared by the .cu files: every CUDA runtime call goes
 * through il_cuda_check, which turns a failure into IL_ERR_MEMORY (out of
 * device memory) or IL_ERR_RUNTIME with the runtime's own message. */
#ifndef IL_CUDA_UTIL_H
#define IL_CUDA_UTIL_H

#include <cuda_runtime.h>
#include "illum/illum.h"

extern "C" {
#include "core/error.h"
}

static inline il_status il_cuda_check(cudaError_t e, const char *what, il_error *err)
{
    if (e == cudaSuccess)
        return IL_OK;
    cudaGetLastError(); /* clear a non-sticky error */
    if (e == cudaErrorMemoryAllocation)
        return il_fail(err, IL_ERR_MEMORY, "CUDA: out of GPU memory in %s", what);
    return il_fail(err, IL_ERR_RUNTIME, "CUDA: %s failed: %s (%s)", what, cudaGetErrorString(e),
                   cudaGetErrorName(e));
}

#endif
