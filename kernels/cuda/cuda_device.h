// The CUDA backend's entry to the device registry. Declared only in builds with CUDA.
#pragma once

#include <memory>
#include <vector>

#include "render/device.h"

namespace pm {

// Empty when no CUDA driver or no CUDA device is present (the binary still runs on OpenCL).
std::vector<DeviceInfo> list_cuda_devices();
// The number of CUDA devices without describing each (0 without a driver or a GPU).
int count_cuda_devices();
std::unique_ptr<Device> create_cuda_device(int index);

}  // namespace pm
