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
// Initialises the driver and device index's primary context (where it exists), so that opening
// the device later in the process does not wait for them. Errors are left to the opening.
void warm_up_cuda_device(int index);

}  // namespace pm
