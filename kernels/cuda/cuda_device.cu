// CUDA implementation of the device interface: one stream, cudaMalloc'd buffers, the buffer
// slot table copied into the kernels' constant-memory KernelGlobals when it changed (once per
// frame), launches through cudaLaunchKernel with the LaunchParams alone, CUB's radix sort for
// sort_pairs, CUDA events for timers. Every call makes its device current first, so several
// CudaDevices can live in one process. Opening a device times its steps for start-up reports
// (render/startup_timing.h): the driver's initialisation, the context, the module load.
#include "kernels/cuda/cuda_device.h"

#include <cuda_runtime.h>

#include <algorithm>
#include <cstdint>
#include <cub/device/device_radix_sort.cuh>
#include <mutex>
#include <string>

#include "kernels/cuda/kernel_table.h"
#include "render/errors.h"

namespace pm {

namespace {

void check(cudaError_t code, const char* call, const char* file, int line) {
  if (code == cudaSuccess) return;
  throw DeviceError(std::string("CUDA: ") + call + " failed with " + cudaGetErrorName(code) + " (" +
                    cudaGetErrorString(code) + ") at " + file + ":" + std::to_string(line));
}
#define PM_CUDA_CHECK(call) check((call), #call, __FILE__, __LINE__)

// How long the process's first CUDA runtime call took: it initialises the driver, whichever call
// it is (the device count of --backend auto, or of opening a device). Reported once, by the first
// device opened; negative: not measured yet, or reported already.
std::mutex driver_init_lock;
double driver_init_ms = -1;
bool driver_init_measured = false;

int cuda_device_count() {
  const StartupClock::time_point start = StartupClock::now();
  int count = 0;
  // Without a driver or a GPU this fails: that means "no CUDA devices", not an error.
  const bool found = cudaGetDeviceCount(&count) == cudaSuccess;
  {
    std::lock_guard<std::mutex> lock(driver_init_lock);
    if (!driver_init_measured) driver_init_ms = ms_between(start, StartupClock::now());
    driver_init_measured = true;
  }
  if (!found) {
    cudaGetLastError();
    return 0;
  }
  return count;
}

// The driver's initialisation time, to the first caller only.
double take_driver_init_ms() {
  std::lock_guard<std::mutex> lock(driver_init_lock);
  const double ms = driver_init_ms;
  driver_init_ms = -1;
  return ms;
}

DeviceInfo describe(int index) {
  cudaDeviceProp prop{};
  PM_CUDA_CHECK(cudaGetDeviceProperties(&prop, index));
  int driver = 0, runtime = 0;
  cudaDriverGetVersion(&driver);
  cudaRuntimeGetVersion(&runtime);
  DeviceInfo info;
  info.backend = "cuda";
  info.index = index;
  info.name = prop.name;
  info.platform = "CUDA runtime " + std::to_string(runtime / 1000) + "." + std::to_string(runtime % 1000 / 10) +
                  ", compute capability " + std::to_string(prop.major) + "." + std::to_string(prop.minor);
  info.driver = "CUDA driver API " + std::to_string(driver / 1000) + "." + std::to_string(driver % 1000 / 10);
  info.memory_bytes = prop.totalGlobalMem;
  info.compute_units = prop.multiProcessorCount;
  return info;
}

class CudaDevice final : public Device {
 public:
  explicit CudaDevice(int index) : index_(index) {
    const double driver_ms = take_driver_init_ms();
    if (driver_ms >= 0) startup_.steps.push_back({"driver init", driver_ms, "the process's first CUDA call"});
    StepClock clock;
    info_ = describe(index);
    startup_.steps.push_back({"device properties", clock.lap_ms(), "cudaGetDeviceProperties"});
    PM_CUDA_CHECK(cudaSetDevice(index));
    PM_CUDA_CHECK(cudaFree(nullptr));  // creates the primary context now, so that its time is its own
    startup_.steps.push_back({"context", clock.lap_ms(), "primary context creation"});
    PM_CUDA_CHECK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking));
    // Pinned, so the copy into constant memory is asynchronous; the event says when the staging
    // copy may be overwritten.
    PM_CUDA_CHECK(cudaMallocHost(&globals_staging_, sizeof(void*) * kBufferSlotCount));
    PM_CUDA_CHECK(cudaEventCreateWithFlags(&globals_copied_, cudaEventDisableTiming));
    startup_.steps.push_back({"stream", clock.lap_ms(), "stream, pinned staging, event"});
    // With lazy loading (CUDA_MODULE_LOADING=LAZY, the default since CUDA 12.2) the module and
    // each kernel load at their first use; asking for every kernel's attributes loads them here,
    // so the first frame's time is the frame's and the load has a row of its own.
    for (size_t i = 0; i < kKernelCount; ++i) {
      cudaFuncAttributes attributes{};
      PM_CUDA_CHECK(cudaFuncGetAttributes(&attributes, pm_cuda_kernel_table[i]));
    }
    startup_.steps.push_back({"module load", clock.lap_ms(), std::to_string(kKernelCount) + " kernels"});
  }

  ~CudaDevice() override {
    activate();
    sort_temp_.reset();
    if (globals_copied_) cudaEventDestroy(globals_copied_);
    if (globals_staging_) cudaFreeHost(globals_staging_);
    if (stream_) cudaStreamDestroy(stream_);
  }

  const DeviceInfo& info() const override { return info_; }

  DeviceBuffer allocate(size_t bytes, const char* what) override {
    activate();
    void* ptr = nullptr;
    cudaError_t err = cudaMalloc(&ptr, bytes > 0 ? bytes : 4);
    if (err != cudaSuccess)
      throw DeviceError(std::string("CUDA: cudaMalloc of ") + std::to_string(bytes) + " bytes for " + what +
                        " failed with " + cudaGetErrorName(err));
    return DeviceBuffer(this, ptr, bytes);
  }

  void release(void* handle) noexcept override {
    cudaSetDevice(index_);
    cudaFree(handle);
  }

  void upload(DeviceBuffer& dst, const void* src, size_t bytes, size_t offset) override {
    if (bytes == 0) return;
    activate();
    PM_CUDA_CHECK(cudaMemcpyAsync(static_cast<char*>(dst.handle()) + offset, src, bytes, cudaMemcpyHostToDevice, stream_));
    // The source is the caller's memory, which may go away as soon as we return.
    PM_CUDA_CHECK(cudaStreamSynchronize(stream_));
  }

  void download(const DeviceBuffer& src, void* dst, size_t bytes, size_t offset) override {
    if (bytes == 0) return;
    activate();
    PM_CUDA_CHECK(cudaMemcpyAsync(dst, static_cast<const char*>(src.handle()) + offset, bytes, cudaMemcpyDeviceToHost, stream_));
    PM_CUDA_CHECK(cudaStreamSynchronize(stream_));
  }

  void fill_zero(DeviceBuffer& dst, size_t bytes) override {
    if (bytes == 0) return;
    activate();
    PM_CUDA_CHECK(cudaMemsetAsync(dst.handle(), 0, bytes, stream_));
  }

  void copy(const DeviceBuffer& src, DeviceBuffer& dst, size_t bytes) override {
    if (bytes == 0) return;
    activate();
    PM_CUDA_CHECK(cudaMemcpyAsync(dst.handle(), src.handle(), bytes, cudaMemcpyDeviceToDevice, stream_));
  }

  void launch(KernelId id, uint32_t work_items, const LaunchParams& params) override {
    if (work_items == 0) return;
    activate();
    upload_globals_if_changed();
    LaunchParams params_copy = params;
    uint32_t items = work_items;
    void* args[2] = {&params_copy, &items};  // cudaLaunchKernel reads each argument through a pointer
    const unsigned block = kCudaBlockThreads;
    const unsigned grid = (work_items + block - 1) / block;
    cudaError_t err = cudaLaunchKernel(pm_cuda_kernel_table[static_cast<int>(id)], dim3(grid), dim3(block), args, 0, stream_);
    if (err != cudaSuccess)
      throw DeviceError(std::string("CUDA: launching kernel ") + kernel_name(id) + " on " +
                        std::to_string(work_items) + " work items failed with " + cudaGetErrorName(err) + " (" +
                        cudaGetErrorString(err) + ")");
  }

  // CUB sorts in the two pairs of buffers it is given (its DoubleBuffer form: the inputs are
  // scratch, as sort_pairs allows), so its temporary storage is only its digit counts, not a
  // third copy of the pairs; the result is copied out when it ends in the inputs.
  void sort_pairs(DeviceBuffer& keys_in, DeviceBuffer& values_in, DeviceBuffer& keys_out, DeviceBuffer& values_out,
                  uint32_t count, int key_bits) override {
    activate();
    cub::DoubleBuffer<uint32_t> keys(static_cast<uint32_t*>(keys_in.handle()), static_cast<uint32_t*>(keys_out.handle()));
    cub::DoubleBuffer<uint32_t> values(static_cast<uint32_t*>(values_in.handle()),
                                       static_cast<uint32_t*>(values_out.handle()));
    // Sized for as many pairs as the output has room for, so that passes whose counts vary within
    // that room do not grow it (device memory flat over passes).
    const size_t room = std::max<size_t>(count, std::min<size_t>(keys_out.bytes() / sizeof(uint32_t), INT32_MAX));
    size_t temp_bytes = 0;
    PM_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, temp_bytes, keys, values, int(room), 0, key_bits, stream_));
    if (sort_temp_.bytes() < temp_bytes) {
      sort_temp_.reset();
      sort_temp_ = allocate(temp_bytes, "CUB radix sort temporary storage");
    }
    temp_bytes = sort_temp_.bytes();
    PM_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(sort_temp_.handle(), temp_bytes, keys, values, int(count), 0,
                                                  key_bits, stream_));
    const size_t bytes = size_t(count) * sizeof(uint32_t);
    if (keys.Current() != keys_out.handle())
      PM_CUDA_CHECK(cudaMemcpyAsync(keys_out.handle(), keys.Current(), bytes, cudaMemcpyDeviceToDevice, stream_));
    if (values.Current() != values_out.handle())
      PM_CUDA_CHECK(cudaMemcpyAsync(values_out.handle(), values.Current(), bytes, cudaMemcpyDeviceToDevice, stream_));
  }

  void synchronize() override {
    activate();
    PM_CUDA_CHECK(cudaStreamSynchronize(stream_));
  }

  TimerEvent record_timer() override {
    activate();
    cudaEvent_t event = nullptr;
    PM_CUDA_CHECK(cudaEventCreate(&event));
    PM_CUDA_CHECK(cudaEventRecord(event, stream_));
    return TimerEvent(event, [](void* e) { cudaEventDestroy(static_cast<cudaEvent_t>(e)); });
  }

  double elapsed_ms(const TimerEvent& start, const TimerEvent& end) override {
    auto stop = static_cast<cudaEvent_t>(end.get());
    PM_CUDA_CHECK(cudaEventSynchronize(stop));
    float ms = 0;
    PM_CUDA_CHECK(cudaEventElapsedTime(&ms, static_cast<cudaEvent_t>(start.get()), stop));
    return ms;
  }

 private:
  // The calling thread's current device becomes this one (a no-op when it already is).
  void activate() {
    int current = -1;
    if (cudaGetDevice(&current) != cudaSuccess || current != index_) PM_CUDA_CHECK(cudaSetDevice(index_));
  }

  // The kernels read their buffer pointers from constant memory (kernels/cuda/kernels.cu):
  // copy the slot table there when a binding changed since the last launch. The copy is queued
  // on the stream, so launches already queued keep the pointers they were launched with.
  void upload_globals_if_changed() {
    if (globals_version_ == slots_version()) return;
    PM_CUDA_CHECK(cudaEventSynchronize(globals_copied_));  // the previous copy has left the staging area
    const auto& table = slots();
    for (size_t i = 0; i < kBufferSlotCount; ++i) globals_staging_[i] = table[i];
    PM_CUDA_CHECK(cudaMemcpyToSymbolAsync(pm_cuda_kernel_globals_symbol(), globals_staging_,
                                          sizeof(void*) * kBufferSlotCount, 0, cudaMemcpyHostToDevice, stream_));
    PM_CUDA_CHECK(cudaEventRecord(globals_copied_, stream_));
    globals_version_ = slots_version();
  }

  int index_ = 0;
  DeviceInfo info_;
  cudaStream_t stream_ = nullptr;
  DeviceBuffer sort_temp_;
  void** globals_staging_ = nullptr;
  cudaEvent_t globals_copied_ = nullptr;
  uint64_t globals_version_ = 0;
};

}  // namespace

int count_cuda_devices() { return cuda_device_count(); }

std::vector<DeviceInfo> list_cuda_devices() {
  std::vector<DeviceInfo> infos;
  int count = cuda_device_count();
  for (int i = 0; i < count; ++i) infos.push_back(describe(i));
  return infos;
}

void warm_up_cuda_device(int index) {
  const int count = cuda_device_count();
  take_driver_init_ms();  // done before the device's opening: not a step of it
  if (index >= 0 && index < count && cudaSetDevice(index) == cudaSuccess) cudaFree(nullptr);
  cudaGetLastError();
}

std::unique_ptr<Device> create_cuda_device(int index) {
  int count = cuda_device_count();
  if (count == 0) throw DeviceError("CUDA: no CUDA device found (no GPU, or no CUDA driver)");
  if (index < 0 || index >= count)
    throw SettingError("device", "no device " + std::to_string(index) + ": CUDA has " + std::to_string(count) +
                     " device(s); see 'pmrender devices'");
  return std::make_unique<CudaDevice>(index);
}

}  // namespace pm
