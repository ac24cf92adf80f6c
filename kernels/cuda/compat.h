/* CUDA backend of the shared kernel code: qualifiers, bit casts, math and atomics as CUDA spells
   them. The shared headers in kernels/common/ use only the PM_* names defined here. */
#ifndef PM_COMPAT_CUDA_H
#define PM_COMPAT_CUDA_H

#include <stdint.h>

#define PM_CUDA_BACKEND 1
#define PM_DEVICE static __device__ __forceinline__
/* A device function kept out of line, with registers of its own (scene_traverse.h says where and
   why). */
#define PM_DEVICE_CALLED static __device__ __noinline__
/* The scene traversal's form (scene_traverse.h): a node's leaves intersected together. */
#define PM_TRAVERSE_LEAVES_TOGETHER 1
/* The edge fit computes its probe points where it uses them (footprint_rim.h): arrays of them
   would live in local memory. */
#define PM_RIM_POINTS_RECOMPUTED 1
#define PM_GLOBAL
#define PM_CONSTANT const
#define PM_RESTRICT __restrict__

typedef unsigned int uint;

#define PM_MAKE_FLOAT4(a, b, c, d) make_float4((a), (b), (c), (d))
#define PM_MAKE_UINT4(a, b, c, d) make_uint4((a), (b), (c), (d))
#define PM_MAKE_FLOAT2(a, b) make_float2((a), (b))

#define PM_AS_FLOAT(i) __int_as_float((int)(i))
#define PM_AS_INT(f) __float_as_int(f)
#define PM_AS_UINT(f) __float_as_uint(f)
#define PM_UINT_AS_FLOAT(u) __uint_as_float((unsigned)(u))

#define pm_sqrtf sqrtf
#define pm_rsqrtf rsqrtf
#define pm_fabsf fabsf
#define pm_fminf fminf
#define pm_fmaxf fmaxf
#define pm_sinf sinf
#define pm_cosf cosf
#define pm_tanf tanf
#define pm_asinf asinf
#define pm_acosf acosf
#define pm_atan2f atan2f
#define pm_powf powf
#define pm_cbrtf cbrtf
#define pm_expf expf
#define pm_logf logf
#define pm_floorf floorf
/* A product rounded on its own, never fused into a following add (watertight ray_triangle). */
#define pm_mul_rn(a, b) __fmul_rn((a), (b))
#define pm_fmaf fmaf
#define pm_copysignf copysignf
#define pm_isfinite(x) isfinite(x)
#define pm_sincosf(a, s, c) sincosf((a), (s), (c))
#define pm_clz(x) __clz((int)(x))
#define pm_min_i(a, b) min((int)(a), (int)(b))
#define pm_max_i(a, b) max((int)(a), (int)(b))
#define pm_min_u(a, b) min((unsigned)(a), (unsigned)(b))

#define pm_atomic_add_u32(p, v) atomicAdd((unsigned*)(p), (unsigned)(v))
#define pm_atomic_add_i32(p, v) atomicAdd((int*)(p), (int)(v))
#define pm_atomic_or_u32(p, v) atomicOr((unsigned*)(p), (unsigned)(v))

/* Read-only data goes through the non-coherent cache. */
/* Orders a work item's global writes before its later atomics (photon map bottom-up pass). */
#define PM_MEMORY_FENCE() __threadfence()

#define PM_LOAD(p) __ldg(p)
/* A load that bypasses the SM's non-coherent L1 cache: data another block wrote in this launch,
   after a fence and an atomic (photon map bottom-up pass). */
static __device__ __forceinline__ float4 pm_load_shared_float4(const float4* p)
{
  const volatile float* f = (const volatile float*)p;
  return make_float4(f[0], f[1], f[2], f[3]);
}
#define PM_LOAD_SHARED_FLOAT4(p) pm_load_shared_float4(p)

#endif
