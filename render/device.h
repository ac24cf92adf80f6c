// The one host interface to a compute device: allocate, copy, fill, launch, sort, time and
// synchronize. The renderer talks only to this; kernels/cuda/ and kernels/opencl/ implement it.
// Every failure throws DeviceError naming the failing call, its file and line.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/kernel_abi.h"
#include "render/startup_timing.h"

namespace pm {

struct DeviceInfo {
  std::string backend;       // "cuda" or "opencl"
  int index = 0;             // index within the backend, as --device takes it
  std::string name;          // e.g. "NVIDIA H200" or "pthread-skylake-avx512"
  std::string platform;      // OpenCL platform or CUDA runtime
  std::string driver;        // driver version
  uint64_t memory_bytes = 0;
  int compute_units = 0;
  bool buffers_in_host_memory = false;  // a CPU device (PoCL): its buffers are the process's memory
  // Work items run in lockstep groups (a GPU's warps): neighbouring work items should share their
  // work's path (the footprints' coverage probes, kernels/common/footprint_probes.h).
  bool lockstep_lanes = true;
};

class Device;

// Owning handle to device memory; released when it goes out of scope.
class DeviceBuffer {
 public:
  DeviceBuffer() = default;
  DeviceBuffer(Device* owner, void* handle, size_t bytes);
  DeviceBuffer(DeviceBuffer&& other) noexcept { *this = std::move(other); }
  DeviceBuffer& operator=(DeviceBuffer&& other) noexcept;
  DeviceBuffer(const DeviceBuffer&) = delete;
  DeviceBuffer& operator=(const DeviceBuffer&) = delete;
  ~DeviceBuffer() { reset(); }

  void reset();
  void* handle() const { return handle_; }
  size_t bytes() const { return bytes_; }
  explicit operator bool() const { return handle_ != nullptr; }

 private:
  Device* owner_ = nullptr;
  void* handle_ = nullptr;
  size_t bytes_ = 0;
};

// A point in the device's command stream; the difference of two is device time.
using TimerEvent = std::shared_ptr<void>;

class Device {
 public:
  virtual ~Device() = default;
  virtual const DeviceInfo& info() const = 0;
  // What opening this device took, step by step (context, program build or cache load, ...).
  const DeviceStartup& startup() const { return startup_; }

  virtual DeviceBuffer allocate(size_t bytes, const char* what) = 0;
  virtual void upload(DeviceBuffer& dst, const void* src, size_t bytes, size_t offset = 0) = 0;
  virtual void download(const DeviceBuffer& src, void* dst, size_t bytes, size_t offset = 0) = 0;
  virtual void fill_zero(DeviceBuffer& dst, size_t bytes) = 0;
  virtual void copy(const DeviceBuffer& src, DeviceBuffer& dst, size_t bytes) = 0;

  // Kernels read their buffers from the slot table; a slot left unbound is null on the device.
  // The host binds a frame's buffers once (render/buffer_table.h); backends pass the table to
  // the device only when it changed (slots_version()).
  void bind(BufferSlot slot, const DeviceBuffer& buffer) { set_slot(slot, buffer.handle()); }
  void unbind(BufferSlot slot) { set_slot(slot, nullptr); }
  // Clears every slot bound to handle (DeviceBuffer::reset calls it: no launch may pass a freed buffer).
  void unbind_handle(const void* handle) {
    for (size_t s = 0; s < slots_.size(); ++s)
      if (slots_[s] == handle) set_slot(static_cast<BufferSlot>(s), nullptr);
  }
  virtual void launch(KernelId kernel, uint32_t work_items, const LaunchParams& params) = 0;

  // Sorts count (key, value) pairs by the low key_bits of the key, stably, from keys_in/values_in
  // into keys_out/values_out (the inputs may be overwritten). CUDA runs CUB; OpenCL runs the
  // portable radix sort kernels (render/portable_sort.h).
  virtual void sort_pairs(DeviceBuffer& keys_in, DeviceBuffer& values_in, DeviceBuffer& keys_out,
                          DeviceBuffer& values_out, uint32_t count, int key_bits) = 0;

  virtual void synchronize() = 0;

  // Device-side timers, for benchmarks only: a render that never records one never pays for them.
  virtual TimerEvent record_timer() = 0;
  virtual double elapsed_ms(const TimerEvent& start, const TimerEvent& end) = 0;

  // Called by DeviceBuffer.
  virtual void release(void* handle) noexcept = 0;

  // Device memory held through DeviceBuffers now, and the most held at once since the last reset.
  uint64_t allocated_bytes() const { return allocated_; }
  uint64_t peak_allocated_bytes() const { return peak_; }
  void reset_peak() { peak_ = allocated_; }
  void note_allocated(size_t bytes) {
    allocated_ += bytes;
    if (allocated_ > peak_) peak_ = allocated_;
  }
  void note_freed(size_t bytes) { allocated_ -= bytes; }
  // What a render may come to hold: what it holds and what its methods have promised to allocate
  // when a pass needs it (DeviceMemoryPromise). The checks before the first frame count this.
  uint64_t needed_bytes() const { return allocated_ + promised_; }

 protected:
  const std::array<void*, kBufferSlotCount>& slots() const { return slots_; }
  DeviceStartup startup_;  // filled by the backend's constructor
  // Increases whenever a slot changes.
  uint64_t slots_version() const { return slots_version_; }

 private:
  void set_slot(BufferSlot slot, void* handle) {
    void*& s = slots_[static_cast<size_t>(slot)];
    if (s != handle) {
      s = handle;
      ++slots_version_;
    }
  }

  std::array<void*, kBufferSlotCount> slots_{};
  uint64_t slots_version_ = 1;
  uint64_t allocated_ = 0, peak_ = 0;
  uint64_t promised_ = 0;
  friend class DeviceMemoryPromise;
};

// Device memory a method does not hold yet but may come to (the photon map grown to the most hits
// a pass may record): the memory checks before the first frame count it as held, so a request
// that could not fit is refused up front, while the buffers themselves are sized by what the
// passes record. Set to what is still missing; the destructor withdraws it.
class DeviceMemoryPromise {
 public:
  explicit DeviceMemoryPromise(Device& device) : device_(&device) {}
  DeviceMemoryPromise(const DeviceMemoryPromise&) = delete;
  DeviceMemoryPromise& operator=(const DeviceMemoryPromise&) = delete;
  ~DeviceMemoryPromise() { set(0); }
  void set(uint64_t bytes) {
    device_->promised_ = device_->promised_ - bytes_ + bytes;
    bytes_ = bytes;
  }

 private:
  Device* device_;
  uint64_t bytes_ = 0;
};

// Every device of every compiled-in backend that can be opened on this machine.
std::vector<DeviceInfo> list_devices();
// Backend names compiled into this binary ("cuda" only when built with CUDA).
std::vector<std::string> compiled_backends();
// backend: "auto" (CUDA when a CUDA device exists, else OpenCL), "cuda" or "opencl".
std::unique_ptr<Device> create_device(const std::string& backend, int index);
// The backend "auto" means on this machine: "cuda" when a CUDA device exists, else "opencl".
std::string resolve_backend(const std::string& backend);
// Initialises backend's driver (CUDA: and device index's primary context; index -1: the driver
// only) so that opening a device later in the process finds it done, while another thread does
// work that needs no device (cli/scene_beside_driver.h). Call it on the thread that lives as long
// as the process: PoCL, started on a thread that then ends, leaves memory that AddressSanitizer
// reports at exit. Errors are left for the opening.
void warm_up_backend(const std::string& backend, int index) noexcept;
// Several devices of one backend; an empty index list means every device of the backend.
std::vector<std::unique_ptr<Device>> create_devices(const std::string& backend, const std::vector<int>& indices);

}  // namespace pm
