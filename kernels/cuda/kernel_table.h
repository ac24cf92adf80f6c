// The CUDA entry points, indexed by KernelId, for cudaLaunchKernel in the host glue.
#pragma once

extern const void* const pm_cuda_kernel_table[];
