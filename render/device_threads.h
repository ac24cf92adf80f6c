// Work on several devices at once, one host thread per device: opening them (an OpenCL device
// compiles its program then), uploading a scene, beginning a frame. A device's calls stay on one
// thread at a time; the devices do not wait for each other.
#pragma once

#include <cstddef>
#include <functional>

namespace pm {

// work(0) .. work(count - 1), each on a thread of its own (work(0) on the calling thread). Once
// all have finished, the failure of the lowest index, if any, is rethrown.
void for_each_device(size_t count, const std::function<void(size_t)>& work);

}  // namespace pm
