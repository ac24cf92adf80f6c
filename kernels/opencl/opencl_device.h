// The OpenCL backend's entry to the device registry: list OpenCL devices of every platform
// (flattened into one index space, as --device takes it) and open one.
#pragma once

#include <memory>
#include <vector>

#include "render/device.h"

namespace pm {

std::vector<DeviceInfo> list_opencl_devices();
std::unique_ptr<Device> create_opencl_device(int index);

}  // namespace pm
