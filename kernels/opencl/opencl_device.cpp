// OpenCL implementation of the device interface: one in-order queue, buffers as cl_mem, the
// embedded kernel source built once per device (or its binary loaded from the program cache:
// opencl_program.h), every buffer slot a kernel argument in PM_BUFFER_LIST order. Kernel
// arguments persist in each cl_kernel, so a launch sets only the slots that changed since that
// kernel's last launch, and its LaunchParams.
#include "kernels/opencl/opencl_device.h"

#include <CL/cl.h>
#include <CL/cl_ext.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>

#include "kernels/opencl/opencl_check.h"
#include "kernels/opencl/opencl_program.h"
#include "render/errors.h"
#include "render/portable_sort.h"

namespace pm {

extern const char kOpenclKernelSource[];
extern const size_t kOpenclKernelSourceSize;

namespace {

struct DeviceEntry {
  cl_platform_id platform;
  cl_device_id device;
};

std::vector<DeviceEntry> enumerate() {
  // One enumeration at a time: devices open on threads of their own (render/host_threads.h), and
  // PoCL counted only one of its devices when two threads made the process's first call at once.
  static std::mutex enumerating;
  std::lock_guard<std::mutex> lock(enumerating);
  std::vector<DeviceEntry> entries;
  cl_uint platform_count = 0;
  // No ICD or no platform is "no OpenCL devices", not an error.
  if (clGetPlatformIDs(0, nullptr, &platform_count) != CL_SUCCESS || platform_count == 0) return entries;
  std::vector<cl_platform_id> platforms(platform_count);
  PM_CL_CHECK(clGetPlatformIDs(platform_count, platforms.data(), nullptr));
  for (cl_platform_id platform : platforms) {
    cl_uint device_count = 0;
    if (clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, 0, nullptr, &device_count) != CL_SUCCESS) continue;
    std::vector<cl_device_id> devices(device_count);
    PM_CL_CHECK(clGetDeviceIDs(platform, CL_DEVICE_TYPE_ALL, device_count, devices.data(), nullptr));
    for (cl_device_id device : devices) entries.push_back({platform, device});
  }
  return entries;
}

std::string gib_text(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.1f GiB", double(bytes) / double(uint64_t(1) << 30));
  return text;
}

// The major version of a PoCL device's driver ("3.1+debian": 3); 0 for other platforms.
int pocl_major_version(const DeviceInfo& info) {
  if (info.platform.find("Portable Computing Language") == std::string::npos) return 0;
  return std::atoi(info.driver.c_str());
}

DeviceInfo describe(const DeviceEntry& entry, int index) {
  DeviceInfo info;
  info.backend = "opencl";
  info.index = index;
  info.name = device_string(entry.device, CL_DEVICE_NAME);
  info.platform = platform_string(entry.platform, CL_PLATFORM_NAME);
  info.driver = device_string(entry.device, CL_DRIVER_VERSION);
  cl_ulong memory = 0;
  cl_uint units = 0;
  PM_CL_CHECK(clGetDeviceInfo(entry.device, CL_DEVICE_GLOBAL_MEM_SIZE, sizeof(memory), &memory, nullptr));
  PM_CL_CHECK(clGetDeviceInfo(entry.device, CL_DEVICE_MAX_COMPUTE_UNITS, sizeof(units), &units, nullptr));
  cl_device_type type = 0;
  PM_CL_CHECK(clGetDeviceInfo(entry.device, CL_DEVICE_TYPE, sizeof(type), &type, nullptr));
  info.memory_bytes = memory;
  info.compute_units = static_cast<int>(units);
  info.buffers_in_host_memory = (type & CL_DEVICE_TYPE_CPU) != 0;
  info.lockstep_lanes = (type & CL_DEVICE_TYPE_GPU) != 0;
  return info;
}

class OpenclDevice final : public Device {
 public:
  // platforms_ms: the enumeration of platforms and devices that found this one.
  OpenclDevice(const DeviceEntry& entry, int index, double platforms_ms)
      : device_(entry.device), platform_(entry.platform) {
    startup_.steps.push_back({"platforms", platforms_ms, "ICD loader and the drivers' initialisation"});
    StepClock clock;
    info_ = describe(entry, index);
    cl_ulong max_allocation = 0;
    PM_CL_CHECK(clGetDeviceInfo(device_, CL_DEVICE_MAX_MEM_ALLOC_SIZE, sizeof(max_allocation), &max_allocation, nullptr));
    max_allocation_ = max_allocation;
    cl_int err = CL_SUCCESS;
    context_ = clCreateContext(nullptr, 1, &device_, nullptr, nullptr, &err);
    PM_CL_CHECK(err);
    queue_ = clCreateCommandQueue(context_, device_, CL_QUEUE_PROFILING_ENABLE, &err);
    PM_CL_CHECK(err);
    startup_.steps.push_back({"context", clock.lap_ms(), "device properties, context, queue"});
    build_program();
  }

  ~OpenclDevice() override {
    sort_scratch_ = PortableSortScratch();
    for (cl_kernel kernel : kernels_)
      if (kernel) clReleaseKernel(kernel);
    if (program_) clReleaseProgram(program_);
    if (queue_) clReleaseCommandQueue(queue_);
    if (context_) clReleaseContext(context_);
  }

  const DeviceInfo& info() const override { return info_; }

  DeviceBuffer allocate(size_t bytes, const char* what) override {
    // A buffer over the device's one-allocation limit fails with CL_INVALID_BUFFER_SIZE; say so
    // with the numbers (PoCL derives the limit from the memory the process may use).
    if (max_allocation_ > 0 && bytes > max_allocation_)
      throw InputError("OpenCL: " + std::string(what) + " needs " + gib_text(bytes) + " in one buffer, but " +
                       info_.name + " allows at most " + gib_text(max_allocation_) +
                       " (CL_DEVICE_MAX_MEM_ALLOC_SIZE); lower --resolution or --photons");
    cl_int err = CL_SUCCESS;
    cl_mem mem = clCreateBuffer(context_, CL_MEM_READ_WRITE, bytes > 0 ? bytes : 4, nullptr, &err);
    if (err != CL_SUCCESS)
      throw DeviceError(std::string("OpenCL: clCreateBuffer of ") + std::to_string(bytes) + " bytes for " + what +
                        " failed with " + cl_error_name(err));
    return DeviceBuffer(this, mem, bytes);
  }

  void release(void* handle) noexcept override { clReleaseMemObject(static_cast<cl_mem>(handle)); }

  void upload(DeviceBuffer& dst, const void* src, size_t bytes, size_t offset) override {
    if (bytes == 0) return;
    PM_CL_CHECK(clEnqueueWriteBuffer(queue_, mem(dst), CL_TRUE, offset, bytes, src, 0, nullptr, nullptr));
  }

  void download(const DeviceBuffer& src, void* dst, size_t bytes, size_t offset) override {
    if (bytes == 0) return;
    PM_CL_CHECK(clEnqueueReadBuffer(queue_, mem(src), CL_TRUE, offset, bytes, dst, 0, nullptr, nullptr));
  }

  void fill_zero(DeviceBuffer& dst, size_t bytes) override {
    if (bytes == 0) return;
    const cl_uint zero = 0;
    PM_CL_CHECK(clEnqueueFillBuffer(queue_, mem(dst), &zero, sizeof(zero), 0, bytes, 0, nullptr, nullptr));
  }

  void copy(const DeviceBuffer& src, DeviceBuffer& dst, size_t bytes) override {
    if (bytes == 0) return;
    PM_CL_CHECK(clEnqueueCopyBuffer(queue_, mem(src), mem(dst), 0, 0, bytes, 0, nullptr, nullptr));
  }

  void launch(KernelId id, uint32_t work_items, const LaunchParams& params) override {
    if (work_items == 0) return;
    const size_t k = static_cast<size_t>(id);
    cl_kernel kernel = kernels_[k];
    if (bound_version_[k] != slots_version()) {
      const auto& table = slots();
      for (size_t slot = 0; slot < kBufferSlotCount; ++slot) {
        cl_mem buffer = static_cast<cl_mem>(table[slot]);
        if (bound_version_[k] != 0 && bound_[k][slot] == buffer) continue;
        PM_CL_CHECK(clSetKernelArg(kernel, cl_uint(slot), sizeof(cl_mem), &buffer));
        bound_[k][slot] = buffer;
      }
      bound_version_[k] = slots_version();
    }
    PM_CL_CHECK(clSetKernelArg(kernel, cl_uint(kBufferSlotCount), sizeof(LaunchParams), &params));
    cl_uint items = work_items;
    PM_CL_CHECK(clSetKernelArg(kernel, cl_uint(kBufferSlotCount + 1), sizeof(cl_uint), &items));
    const size_t local = 64;
    const size_t global = (size_t(work_items) + local - 1) / local * local;
    cl_int err = clEnqueueNDRangeKernel(queue_, kernel, 1, nullptr, &global, &local, 0, nullptr, nullptr);
    if (err != CL_SUCCESS)
      throw DeviceError(std::string("OpenCL: launching kernel ") + kernel_name(id) + " on " +
                        std::to_string(work_items) + " work items failed with " + cl_error_name(err));
  }

  void sort_pairs(DeviceBuffer& keys_in, DeviceBuffer& values_in, DeviceBuffer& keys_out, DeviceBuffer& values_out,
                  uint32_t count, int key_bits) override {
    portable_sort_pairs(*this, sort_scratch_, keys_in, values_in, keys_out, values_out, count, key_bits);
  }

  void synchronize() override { PM_CL_CHECK(clFinish(queue_)); }

  TimerEvent record_timer() override {
    cl_event event = nullptr;
    PM_CL_CHECK(clEnqueueMarkerWithWaitList(queue_, 0, nullptr, &event));
    return TimerEvent(event, [](void* e) { clReleaseEvent(static_cast<cl_event>(e)); });
  }

  double elapsed_ms(const TimerEvent& start, const TimerEvent& end) override {
    cl_event events[2] = {static_cast<cl_event>(start.get()), static_cast<cl_event>(end.get())};
    PM_CL_CHECK(clWaitForEvents(2, events));
    cl_ulong t0 = 0, t1 = 0;
    PM_CL_CHECK(clGetEventProfilingInfo(events[0], CL_PROFILING_COMMAND_END, sizeof(t0), &t0, nullptr));
    PM_CL_CHECK(clGetEventProfilingInfo(events[1], CL_PROFILING_COMMAND_END, sizeof(t1), &t1, nullptr));
    return double(t1 - t0) * 1e-6;
  }

 private:
  static cl_mem mem(const DeviceBuffer& buffer) { return static_cast<cl_mem>(buffer.handle()); }

  void build_program() {
    // No -cl-fast-relaxed-math: it implies finite-math-only, and the slab tests rely on IEEE
    // infinities for axis-parallel rays.
    OpenclProgramRequest request;
    request.context = context_;
    request.device = device_;
    request.platform = platform_;
    request.source = kOpenclKernelSource;
    request.source_size = kOpenclKernelSourceSize;
    request.options = "-cl-std=CL1.2 -cl-mad-enable";
    // PoCL 5 shares one compiled library between identical programs of two of its CPU devices and
    // then releases it twice (an assertion in pocl_release_dlhandle_cache aborted the process):
    // there the device's index makes each device's program its own. PoCL 3 (Debian 12's) runs two
    // devices on one program (tests/opencl/multi_device_cli_test.cpp), which it then compiles once
    // rather than once per device (about 30 s on 2 cores when its kernel cache is cold).
    if (pocl_major_version(info_) >= 4) request.options += " -D PM_OPENCL_DEVICE_INDEX=" + std::to_string(info_.index);
    // As on CUDA, the tracing kernels are faster with more resident warps than registers: capped
    // at 64 registers for the whole program, the path tracer's pass ran 31 % and the 1080p photon
    // frames 4.6-13.9 % faster on an H100 (docs/benchmarks.md, "Registers against occupancy";
    // the CUDA backend caps the same kernels with launch bounds).
    if (info_.platform.find("NVIDIA") != std::string::npos) request.options += " -cl-nv-maxrregcount=64";
    program_ = build_opencl_program(request, ProgramCache(program_cache_settings_from_environment()), startup_);
    StepClock clock;
    cl_int err = CL_SUCCESS;
    for (size_t i = 0; i < kKernelCount; ++i) {
      std::string name = std::string("pm_") + kernel_name(static_cast<KernelId>(i));
      kernels_[i] = clCreateKernel(program_, name.c_str(), &err);
      if (err != CL_SUCCESS)
        throw DeviceError("OpenCL: clCreateKernel(" + name + ") failed with " + cl_error_name(err));
    }
    startup_.steps.push_back({"kernels", clock.lap_ms(), std::to_string(kKernelCount) + " clCreateKernel"});
  }

  DeviceInfo info_;
  uint64_t max_allocation_ = 0;  // CL_DEVICE_MAX_MEM_ALLOC_SIZE
  cl_device_id device_ = nullptr;
  cl_platform_id platform_ = nullptr;
  cl_context context_ = nullptr;
  cl_command_queue queue_ = nullptr;
  cl_program program_ = nullptr;
  cl_kernel kernels_[kKernelCount] = {};
  // The buffer arguments each kernel was last given, and the slot table version they match
  // (0: none set yet).
  std::array<std::array<cl_mem, kBufferSlotCount>, kKernelCount> bound_{};
  std::array<uint64_t, kKernelCount> bound_version_{};
  PortableSortScratch sort_scratch_;
};

}  // namespace

std::vector<DeviceInfo> list_opencl_devices() {
  std::vector<DeviceInfo> infos;
  std::vector<DeviceEntry> entries = enumerate();
  for (size_t i = 0; i < entries.size(); ++i) infos.push_back(describe(entries[i], static_cast<int>(i)));
  return infos;
}

void warm_up_opencl() { enumerate(); }

std::unique_ptr<Device> create_opencl_device(int index) {
  StepClock clock;
  std::vector<DeviceEntry> entries = enumerate();
  const double platforms_ms = clock.lap_ms();
  if (entries.empty())
    throw DeviceError("OpenCL: no OpenCL device found (is an ICD such as pocl-opencl-icd installed?)");
  if (index < 0 || index >= static_cast<int>(entries.size()))
    throw SettingError("device", "no device " + std::to_string(index) + ": OpenCL has " + std::to_string(entries.size()) +
                     " device(s); see 'pmrender devices'");
  return std::make_unique<OpenclDevice>(entries[index], index, platforms_ms);
}

}  // namespace pm
