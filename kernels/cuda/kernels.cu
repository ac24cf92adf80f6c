// CUDA entry points: one __global__ function per entry of PM_KERNEL_LIST, generated below. Each
// computes its work-item index, checks bounds and calls the shared stage function.
#include "kernels/cuda/compat.h"
#include "kernels/common/stages.h"
#include "kernels/cuda/kernel_table.h"

#define PM_CUDA_PARAM(type, name) type* __restrict__ name,
#define PM_CUDA_BIND(type, name) kg.name = name;
#define PM_CUDA_ENTRY(kernel)                                                                   \
  __global__ void pm_##kernel(PM_BUFFER_LIST(PM_CUDA_PARAM) const LaunchParams params, uint work_items) \
  {                                                                                             \
    uint index = blockIdx.x * blockDim.x + threadIdx.x;                                         \
    if (index >= work_items) return;                                                            \
    KernelGlobals kg;                                                                           \
    PM_BUFFER_LIST(PM_CUDA_BIND)                                                                \
    kernel_##kernel(&kg, &params, index);                                                       \
  }
PM_KERNEL_LIST(PM_CUDA_ENTRY)

#define PM_CUDA_TABLE_ENTRY(kernel) reinterpret_cast<const void*>(&pm_##kernel),
const void* const pm_cuda_kernel_table[] = {PM_KERNEL_LIST(PM_CUDA_TABLE_ENTRY)};
