// CUDA entry points: one __global__ function per entry of PM_KERNEL_LIST, generated below. Each
// computes its work-item index, checks bounds and calls the shared stage function with the
// buffer pointers of the constant-memory KernelGlobals (bound once per frame by the host, as
// Cycles binds its data arrays) and the launch's own parameters.
#include "kernels/cuda/compat.h"
#include "kernels/common/stages.h"
#include "kernels/cuda/kernel_table.h"

__constant__ KernelGlobals pm_kernel_globals;

// Registers against occupancy. Left to itself ptxas gives the tracing kernels 89 to 157 registers
// (the path tracer 157, final gathering 155, the bias control 132, the photon trace 95, the
// footprints 89, the density-estimation gathers with their pixel tiles' walks 91 to 93: sm_90,
// CUDA 12-13), so that few warps are resident to hide the traversal's memory latency. Eight blocks
// per SM cap them at 64 registers, some of it spilled to L1: measured on an H100 (docs/benchmarks.md,
// "Registers against occupancy"), the path tracer's pass 30 % and final gathering's 46 % faster,
// the 1080p photon frames up to 5 %; on an H200 the tiled gathers at 1080p 1.25 to 1.31 times
// faster than unbounded and 2 to 5 % faster than at seven blocks, 72 registers (1 to 2 % slower at
// the paper's 512 x 512; "Pixel tiles walk the photon map together"). The knn gather gets no
// launch bounds at all.
#define PM_CUDA_BOUNDS_0 __launch_bounds__(kCudaBlockThreads, 8)
#define PM_CUDA_BOUNDS_1
// PM_CUDA_UNBOUNDED(kernel) is 1 for the kernels named by a PM_CUDA_UNBOUNDED_<kernel> below, else
// 0 (the macro's probe: a defined name supplies a second argument).
#define PM_CUDA_UNBOUNDED_knn_gather ~, 1
#define PM_CUDA_SECOND(a, b, ...) b
#define PM_CUDA_PROBE(...) PM_CUDA_SECOND(__VA_ARGS__, 0, 0)
#define PM_CUDA_UNBOUNDED(kernel) PM_CUDA_PROBE(PM_CUDA_UNBOUNDED_##kernel)
#define PM_CUDA_CAT(a, b) PM_CUDA_CAT_(a, b)
#define PM_CUDA_CAT_(a, b) a##b
#define PM_CUDA_BOUNDS(kernel) PM_CUDA_CAT(PM_CUDA_BOUNDS_, PM_CUDA_UNBOUNDED(kernel))

#define PM_CUDA_ENTRY(kernel)                                                        \
  __global__ void PM_CUDA_BOUNDS(kernel) pm_##kernel(const LaunchParams params, uint work_items) \
  {                                                                                  \
    uint index = blockIdx.x * blockDim.x + threadIdx.x;                              \
    if (index >= work_items) return;                                                 \
    kernel_##kernel(&pm_kernel_globals, &params, index);                             \
  }
PM_KERNEL_LIST(PM_CUDA_ENTRY)

#define PM_CUDA_TABLE_ENTRY(kernel) reinterpret_cast<const void*>(&pm_##kernel),
const void* const pm_cuda_kernel_table[] = {PM_KERNEL_LIST(PM_CUDA_TABLE_ENTRY)};

const void* pm_cuda_kernel_globals_symbol() { return reinterpret_cast<const void*>(&pm_kernel_globals); }
