// The OpenCL backend's entry to the device registry: list OpenCL devices of every platform
// (flattened into one index space, as --device takes it) and open one.
#pragma once

#include <memory>
#include <vector>

#include "render/device.h"

namespace pm {

std::vector<DeviceInfo> list_opencl_devices();
std::unique_ptr<Device> create_opencl_device(int index);
// Enumerates the platforms and devices once (the ICD loader and the drivers initialise), so that
// opening a device later in the process does not wait for it.
void warm_up_opencl();

}  // namespace pm
