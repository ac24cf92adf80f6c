/* OpenCL entry points: one __kernel per entry of PM_KERNEL_LIST, generated below. Each computes
   its work-item index, checks bounds and calls the shared stage function. This file and every
   header it includes are flattened into the binary at build time (embed_kernel_source.cpp). */
#include "kernels/opencl/compat.h"
#include "kernels/common/stages.h"

#define PM_CL_PARAM(group, type, name, extent, per) __global type* restrict name,
#define PM_CL_BIND(group, type, name, extent, per) kg.name = name;
#define PM_CL_ENTRY(kernel)                                                                     \
  __kernel void pm_##kernel(PM_BUFFER_LIST(PM_CL_PARAM) const LaunchParams params, const uint work_items) \
  {                                                                                             \
    uint index = (uint)get_global_id(0);                                                        \
    if (index >= work_items) return;                                                            \
    KernelGlobals kg;                                                                           \
    PM_BUFFER_LIST(PM_CL_BIND)                                                                  \
    kernel_##kernel(&kg, &params, index);                                                       \
  }
PM_KERNEL_LIST(PM_CL_ENTRY)
