// The CUDA entry points, indexed by KernelId, and the constant-memory KernelGlobals they read,
// for cudaLaunchKernel and cudaMemcpyToSymbolAsync in the host glue, and the block size both sides
// agree on.
#pragma once

// Threads per block of every launch; the entry points' launch bounds are stated for it.
constexpr unsigned kCudaBlockThreads = 128;

extern const void* const pm_cuda_kernel_table[];
const void* pm_cuda_kernel_globals_symbol();
