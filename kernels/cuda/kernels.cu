// CUDA entry points: one __global__ function per entry of PM_KERNEL_LIST, generated below. Each
// computes its work-item index, checks bounds and calls the shared stage function with the
// buffer pointers of the constant-memory KernelGlobals (bound once per frame by the host, as
// Cycles binds its data arrays) and the launch's own parameters.
#include "kernels/cuda/compat.h"
#include "kernels/common/stages.h"
#include "kernels/cuda/kernel_table.h"

__constant__ KernelGlobals pm_kernel_globals;

#define PM_CUDA_ENTRY(kernel)                                                        \
  __global__ void pm_##kernel(const LaunchParams params, uint work_items)            \
  {                                                                                  \
    uint index = blockIdx.x * blockDim.x + threadIdx.x;                              \
    if (index >= work_items) return;                                                 \
    kernel_##kernel(&pm_kernel_globals, &params, index);                             \
  }
PM_KERNEL_LIST(PM_CUDA_ENTRY)

#define PM_CUDA_TABLE_ENTRY(kernel) reinterpret_cast<const void*>(&pm_##kernel),
const void* const pm_cuda_kernel_table[] = {PM_KERNEL_LIST(PM_CUDA_TABLE_ENTRY)};

const void* pm_cuda_kernel_globals_symbol() { return reinterpret_cast<const void*>(&pm_kernel_globals); }
