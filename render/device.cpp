// Backend-neutral parts of the device interface: buffer ownership, names for the generated
// enums, and the registry that lists devices and opens one by backend name.
#include "render/device.h"

#include <utility>

#include "kernels/opencl/opencl_device.h"
#include "render/host_threads.h"
#include "render/errors.h"
#if PMRENDER_HAVE_CUDA
#include "kernels/cuda/cuda_device.h"
#endif

namespace pm {

DeviceBuffer::DeviceBuffer(Device* owner, void* handle, size_t bytes) : owner_(owner), handle_(handle), bytes_(bytes) {
  if (owner_) owner_->note_allocated(bytes_);
}

DeviceBuffer& DeviceBuffer::operator=(DeviceBuffer&& other) noexcept {
  if (this != &other) {
    reset();
    owner_ = std::exchange(other.owner_, nullptr);
    handle_ = std::exchange(other.handle_, nullptr);
    bytes_ = std::exchange(other.bytes_, 0);
  }
  return *this;
}

void DeviceBuffer::reset() {
  if (owner_ && handle_) {
    owner_->unbind_handle(handle_);
    owner_->release(handle_);
    owner_->note_freed(bytes_);
  }
  owner_ = nullptr;
  handle_ = nullptr;
  bytes_ = 0;
}

const char* kernel_name(KernelId id) {
  static const char* const names[] = {
#define PM_KERNEL_NAME(name) #name,
      PM_KERNEL_LIST(PM_KERNEL_NAME)
#undef PM_KERNEL_NAME
  };
  return names[static_cast<int>(id)];
}

const char* buffer_slot_name(BufferSlot slot) {
  static const char* const names[] = {
#define PM_SLOT_NAME(group, type, name, extent, per) #name,
      PM_BUFFER_LIST(PM_SLOT_NAME)
#undef PM_SLOT_NAME
  };
  return names[static_cast<int>(slot)];
}

std::vector<std::string> compiled_backends() {
#if PMRENDER_HAVE_CUDA
  return {"cuda", "opencl"};
#else
  return {"opencl"};
#endif
}

std::vector<DeviceInfo> list_devices() {
  std::vector<DeviceInfo> all;
#if PMRENDER_HAVE_CUDA
  for (DeviceInfo& info : list_cuda_devices()) all.push_back(std::move(info));
#endif
  for (DeviceInfo& info : list_opencl_devices()) all.push_back(std::move(info));
  return all;
}

std::string resolve_backend(const std::string& backend) {
  if (backend != "auto") return backend;
#if PMRENDER_HAVE_CUDA
  if (count_cuda_devices() > 0) return "cuda";
#endif
  return "opencl";
}

std::vector<std::unique_ptr<Device>> create_devices(const std::string& backend, const std::vector<int>& indices) {
  const std::string resolved = resolve_backend(backend);
  std::vector<int> chosen = indices;
  if (chosen.empty())
    for (const DeviceInfo& info : list_devices())
      if (info.backend == resolved) chosen.push_back(info.index);
  if (chosen.empty()) throw DeviceError(resolved + ": no device found");
  // Each device opens on a thread of its own: an OpenCL device compiles its program on opening
  // (seconds on some drivers), and the devices need not wait for each other.
  std::vector<std::unique_ptr<Device>> devices(chosen.size());
  for_each_device(chosen.size(), [&](size_t i) { devices[i] = create_device(resolved, chosen[i]); });
  return devices;
}

void warm_up_backend(const std::string& backend, int index) noexcept {
  try {
#if PMRENDER_HAVE_CUDA
    if (backend == "cuda" || (backend == "auto" && count_cuda_devices() > 0)) {
      warm_up_cuda_device(index);
      return;
    }
#endif
    if (backend == "opencl" || backend == "auto") warm_up_opencl();
  } catch (...) {
    // The device's opening meets the same error and reports it.
  }
}

std::unique_ptr<Device> create_device(const std::string& backend, int index) {
  if (backend == "auto") {
#if PMRENDER_HAVE_CUDA
    // Counted, not listed: describing every GPU of the machine costs a properties query each.
    if (count_cuda_devices() > 0) return create_cuda_device(index);
#endif
    return create_opencl_device(index);
  }
  if (backend == "cuda") {
#if PMRENDER_HAVE_CUDA
    return create_cuda_device(index);
#else
    throw SettingError("backend", "cuda: this pmrender was built without CUDA (rebuild with nvcc available)");
#endif
  }
  if (backend == "opencl") return create_opencl_device(index);
  throw SettingError("backend", "unknown backend '" + backend + "' (expected auto, cuda or opencl)");
}

}  // namespace pm
