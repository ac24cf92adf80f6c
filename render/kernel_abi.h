// The host's view of the kernel ABI: the shared structs from kernels/common/types.h, the
// BufferSlot and KernelId enums generated from the same X-macro lists the backends expand.
#pragma once

#include <cstddef>
#include <cstdint>

#if defined(__CUDACC__)
#include "kernels/cuda/compat.h"  // CUDA's own float4 in the CUDA backend's host glue
#else
#include "kernels/common/compat_host.h"
#endif
#include "kernels/common/types.h"
#include "kernels/common/buffers.h"
#include "kernels/common/kernel_list.h"

namespace pm {

// The shared structs' sizes, as every device compiler must see them too (layout_probe).
static_assert(sizeof(Material) == 64 && sizeof(PointLight) == 48 && sizeof(CameraParams) == 64,
              "shared structs hold only float4 members");
static_assert(sizeof(LaunchParams) % 16 == 0, "LaunchParams is a whole number of 16-byte rows");

enum class BufferSlot : int {
#define PM_SLOT_ENUM(group, type, name, extent, per) name,
  PM_BUFFER_LIST(PM_SLOT_ENUM)
#undef PM_SLOT_ENUM
};
#define PM_SLOT_COUNT(group, type, name, extent, per) +1
constexpr size_t kBufferSlotCount = 0 PM_BUFFER_LIST(PM_SLOT_COUNT);
#undef PM_SLOT_COUNT

enum class KernelId : int {
#define PM_KERNEL_ENUM(name) name,
  PM_KERNEL_LIST(PM_KERNEL_ENUM)
#undef PM_KERNEL_ENUM
};
#define PM_KERNEL_COUNT(name) +1
constexpr size_t kKernelCount = 0 PM_KERNEL_LIST(PM_KERNEL_COUNT);
#undef PM_KERNEL_COUNT

// "camera_pass" etc., for OpenCL kernel lookup and error messages.
const char* kernel_name(KernelId id);
const char* buffer_slot_name(BufferSlot slot);

}  // namespace pm
