// The CUDA entry points, indexed by KernelId, and the constant-memory KernelGlobals they read,
// for cudaLaunchKernel and cudaMemcpyToSymbolAsync in the host glue.
#pragma once

extern const void* const pm_cuda_kernel_table[];
const void* pm_cuda_kernel_globals_symbol();
