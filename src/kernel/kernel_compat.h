/* Qualifiers that let one header compile for both targets, in the style of
 * Cycles' kernel/device/{cpu,gpu}/compat.h: under nvcc every kernel function
 * is __host__ __device__ (the CPU tests and the GPU run the same code), under
 * gcc/clang a plain static inline C17 function.
 *
 * Rules for everything under src/kernel/ (so that nvcc, which compiles .cu
 * files as C++, accepts it): no compound literals, no designated
 * initialisers, no VLAs, no libc calls except <math.h> float functions
 * (sqrtf, fabsf, ...), no globals, no allocation.  The CPU-only builder
 * (bvh_build.c) is the exception: it is never compiled by nvcc. */
#ifndef IL_KERNEL_COMPAT_H
#define IL_KERNEL_COMPAT_H

#include <math.h>
#include <stdint.h>
#if !defined(__cplusplus)
#include <stdbool.h>
#endif

#if defined(__CUDACC__)
#define IL_DEVICE __host__ __device__
#define IL_DEVICE_INLINE static __forceinline__ __host__ __device__
#define IL_KERNEL_GPU 1
#else
#define IL_DEVICE
#define IL_DEVICE_INLINE static inline
#define IL_KERNEL_GPU 0
#endif

#endif
