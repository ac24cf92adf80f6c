/* Host "backend" for the shared kernel code: lets plain C++ (unit tests, host reference
   computations) include kernels/common/ headers and call stage functions directly.
   Mirrors kernels/cuda/compat.h and kernels/opencl/compat.h; see docs/architecture.md. */
#ifndef PM_COMPAT_HOST_H
#define PM_COMPAT_HOST_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define PM_HOST_BACKEND 1
#define PM_DEVICE static inline
#define PM_DEVICE_CALLED static inline
#define PM_TRAVERSE_LEAVES_TOGETHER 1 /* the GPUs' schedule, which the host tests check */
#define PM_RIM_POINTS_RECOMPUTED 1    /* likewise the GPUs' edge fit (footprint_rim.h) */
#define PM_GLOBAL
#define PM_CONSTANT const
#define PM_RESTRICT __restrict__

typedef uint32_t uint;

typedef struct alignas(16) float4 { float x, y, z, w; } float4;
typedef struct alignas(16) uint4 { uint32_t x, y, z, w; } uint4;
typedef struct alignas(8) float2 { float x, y; } float2;

#define PM_MAKE_FLOAT4(a, b, c, d) (float4{(a), (b), (c), (d)})
#define PM_MAKE_UINT4(a, b, c, d) (uint4{(a), (b), (c), (d)})
#define PM_MAKE_FLOAT2(a, b) (float2{(a), (b)})

PM_DEVICE float pm_int_bits_as_float(int32_t i) { float f; memcpy(&f, &i, 4); return f; }
PM_DEVICE int32_t pm_float_as_int_bits(float f) { int32_t i; memcpy(&i, &f, 4); return i; }
PM_DEVICE float pm_uint_bits_as_float(uint32_t i) { float f; memcpy(&f, &i, 4); return f; }
PM_DEVICE uint32_t pm_float_as_uint_bits(float f) { uint32_t i; memcpy(&i, &f, 4); return i; }
#define PM_AS_FLOAT(i) pm_int_bits_as_float((int32_t)(i))
#define PM_AS_INT(f) pm_float_as_int_bits(f)
#define PM_AS_UINT(f) pm_float_as_uint_bits(f)
#define PM_UINT_AS_FLOAT(u) pm_uint_bits_as_float((uint32_t)(u))

#define pm_sqrtf sqrtf
#define pm_rsqrtf(x) (1.0f / sqrtf(x))
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
#define pm_mul_rn(a, b) ((a) * (b))
#define pm_fmaf fmaf
#define pm_copysignf copysignf
#define pm_isfinite(x) isfinite(x)
PM_DEVICE void pm_sincosf(float a, float* s, float* c) { *s = sinf(a); *c = cosf(a); }
PM_DEVICE int pm_clz(uint32_t x) { return x == 0 ? 32 : __builtin_clz(x); }
PM_DEVICE int pm_min_i(int a, int b) { return a < b ? a : b; }
PM_DEVICE int pm_max_i(int a, int b) { return a > b ? a : b; }
PM_DEVICE uint32_t pm_min_u(uint32_t a, uint32_t b) { return a < b ? a : b; }

/* Host tests run single-threaded, so plain read-modify-write is an exact atomic. */
PM_DEVICE uint32_t pm_atomic_add_u32(uint32_t* p, uint32_t v) { uint32_t old = *p; *p = old + v; return old; }
PM_DEVICE int32_t pm_atomic_add_i32(int32_t* p, int32_t v) { int32_t old = *p; *p = old + v; return old; }
PM_DEVICE uint32_t pm_atomic_or_u32(uint32_t* p, uint32_t v) { uint32_t old = *p; *p = old | v; return old; }

/* Read-only loads: plain loads on the host. */
/* Orders a work item's global writes before its later atomics (photon map bottom-up pass). */
#define PM_MEMORY_FENCE() ((void)0)

#define PM_LOAD(p) (*(p))
#define PM_LOAD_SHARED_FLOAT4(p) (*(p))

#endif
