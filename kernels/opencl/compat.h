/* OpenCL C backend of the shared kernel code: qualifiers, bit casts, math and atomics as
   OpenCL C 1.2 spells them (PoCL and vendor GPU drivers). Embedded into the binary together
   with kernels/common/ at build time. */
#ifndef PM_COMPAT_OPENCL_H
#define PM_COMPAT_OPENCL_H

#define PM_OPENCL_BACKEND 1
#define PM_DEVICE static inline
/* The scene traversal (scene_traverse.h) on NVIDIA's OpenCL as on CUDA: out of line, a node's leaves
   intersected together. PoCL inlines it (a CPU's work items do not share a register file) and keeps
   one loop, where the two loops made the photon trace and the coverage probes 10-21 % slower
   (docs/benchmarks.md, "Leaves intersected together on PoCL"). */
#if defined(cl_nv_pragma_unroll)
#define PM_DEVICE_CALLED static __attribute__((noinline))
#define PM_TRAVERSE_LEAVES_TOGETHER 1
#define PM_RIM_POINTS_RECOMPUTED 1 /* footprint_rim.h: as on CUDA */
#else
#define PM_DEVICE_CALLED static inline
#define PM_TRAVERSE_LEAVES_TOGETHER 0
#define PM_RIM_POINTS_RECOMPUTED 0 /* footprint_rim.h: a CPU keeps the edge fit's points in cache */
#endif
#define PM_GLOBAL __global
#define PM_CONSTANT __constant
#define PM_RESTRICT restrict

/* Random123's OpenCL feature header defines uint32_t and uint64_t; take them from there so the
   typedefs exist exactly once. */
#include <Random123/philox.h>
typedef int int32_t;

#define PM_MAKE_FLOAT4(a, b, c, d) ((float4)((a), (b), (c), (d)))
#define PM_MAKE_UINT4(a, b, c, d) ((uint4)((a), (b), (c), (d)))
#define PM_MAKE_FLOAT2(a, b) ((float2)((a), (b)))

#define PM_AS_FLOAT(i) as_float((int)(i))
#define PM_AS_INT(f) as_int(f)
#define PM_AS_UINT(f) as_uint(f)
#define PM_UINT_AS_FLOAT(u) as_float((uint)(u))

#define pm_sqrtf sqrt
#define pm_rsqrtf rsqrt
#define pm_fabsf fabs
#define pm_fminf fmin
#define pm_fmaxf fmax
/* On NVIDIA's OpenCL the hardware's functions, as CUDA's --use_fast_math gives its kernels; PoCL
   keeps the full ones. Sine and cosine: the full-range functions (with their Payne-Hanek
   reduction) are inlined at each of the footprint gather's sines and cosines, 84 in CUDA's PTX of
   it, and cost NVIDIA's production gathers 0.7 to 1.8 % (docs/benchmarks.md, "NVIDIA's OpenCL
   against CUDA"). The power, only of the glossy lobe (brdf.h), whose bases are never negative
   (cosines and uniform numbers): `native_powr`, an exp2 of a log2, where `pow` put a
   full-precision function of about a hundred instructions into each gather loop
   (docs/benchmarks.md, "The same count since"). */
#if defined(cl_nv_pragma_unroll)
#define pm_sinf native_sin
#define pm_cosf native_cos
#define pm_sincosf(a, s, c) (*(s) = native_sin(a), *(c) = native_cos(a))
#define pm_powf native_powr
#else
#define pm_sinf sin
#define pm_cosf cos
#define pm_sincosf(a, s, c) (*(s) = sincos((a), (c)))
#define pm_powf pow
#endif
#define pm_tanf tan
#define pm_asinf asin
#define pm_acosf acos
#define pm_atan2f atan2
#define pm_cbrtf cbrt
#define pm_expf exp
#define pm_logf log
#define pm_floorf floor
/* A product rounded on its own, never fused into a following add: a fused a*b+c breaks
   ray_triangle's watertight edge tests (cracks, hits on point triangles). Contraction is off in
   this function's body only (C99's scope of the pragma); everywhere else a*b+c may fuse, as on
   CUDA, where only these products are unfused (__fmul_rn). */
static inline float pm_mul_rn(float a, float b)
{
#pragma OPENCL FP_CONTRACT OFF
  return a * b;
}
#define pm_fmaf fma
#define pm_copysignf copysign
#define pm_isfinite(x) isfinite(x)
#define pm_clz(x) ((int)clz((uint)(x)))
#define pm_min_i(a, b) min((int)(a), (int)(b))
#define pm_max_i(a, b) max((int)(a), (int)(b))
#define pm_min_u(a, b) min((uint)(a), (uint)(b))

#define pm_atomic_add_u32(p, v) atomic_add((volatile __global uint*)(p), (uint)(v))
#define pm_atomic_add_i32(p, v) atomic_add((volatile __global int*)(p), (int)(v))
#define pm_atomic_or_u32(p, v) atomic_or((volatile __global uint*)(p), (uint)(v))

/* Orders a work item's global writes before its later atomics (photon map bottom-up pass), for
   every work item of the launch: the sibling that reads them may run on another multiprocessor.
   OpenCL 1.2's mem_fence promises order within the work item only, and NVIDIA's driver keeps it
   that narrow: the same frame rendered twice there differed (rmse 1.4e-4, docs/gpu-notes.md), as
   the second arrival at a node read a stale box. NVIDIA's compiler takes inline PTX (it defines
   cl_nv_pragma_unroll): a device-wide membar.gl there; elsewhere (PoCL's threads share one
   coherent memory) the OpenCL fence. */
#if defined(cl_nv_pragma_unroll)
#define PM_MEMORY_FENCE() asm volatile("membar.gl;" ::: "memory")
#else
#define PM_MEMORY_FENCE() mem_fence(CLK_GLOBAL_MEM_FENCE)
#endif

#define PM_LOAD(p) (*(p))
/* A load that bypasses the multiprocessor's non-coherent L1 cache: data another work group wrote
   in this launch, after a fence and an atomic (photon map bottom-up pass). */
#define PM_LOAD_SHARED_FLOAT4(p) (*(volatile __global const float4*)(p))

#endif
