// CUDA implementation of the device interface: one stream, cudaMalloc'd buffers, every buffer
// slot passed as a kernel argument in PM_BUFFER_LIST order through cudaLaunchKernel, CUB's
// radix sort for sort_pairs, CUDA events for timers.
#include "kernels/cuda/cuda_device.h"

#include <cuda_runtime.h>

#include <cub/device/device_radix_sort.cuh>
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

int cuda_device_count() {
  int count = 0;
  // Without a driver or a GPU this fails: that means "no CUDA devices", not an error.
  if (cudaGetDeviceCount(&count) != cudaSuccess) {
    cudaGetLastError();
    return 0;
  }
  return count;
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
  explicit CudaDevice(int index) {
    info_ = describe(index);
    PM_CUDA_CHECK(cudaSetDevice(index));
    PM_CUDA_CHECK(cudaStreamCreateWithFlags(&stream_, cudaStreamNonBlocking));
  }

  ~CudaDevice() override {
    sort_temp_.reset();
    if (stream_) cudaStreamDestroy(stream_);
  }

  const DeviceInfo& info() const override { return info_; }

  DeviceBuffer allocate(size_t bytes, const char* what) override {
    void* ptr = nullptr;
    cudaError_t err = cudaMalloc(&ptr, bytes > 0 ? bytes : 4);
    if (err != cudaSuccess)
      throw DeviceError(std::string("CUDA: cudaMalloc of ") + std::to_string(bytes) + " bytes for " + what +
                        " failed with " + cudaGetErrorName(err));
    return DeviceBuffer(this, ptr, bytes);
  }

  void release(void* handle) noexcept override { cudaFree(handle); }

  void upload(DeviceBuffer& dst, const void* src, size_t bytes, size_t offset) override {
    if (bytes == 0) return;
    PM_CUDA_CHECK(cudaMemcpyAsync(static_cast<char*>(dst.handle()) + offset, src, bytes, cudaMemcpyHostToDevice, stream_));
    // The source is the caller's memory, which may go away as soon as we return.
    PM_CUDA_CHECK(cudaStreamSynchronize(stream_));
  }

  void download(const DeviceBuffer& src, void* dst, size_t bytes, size_t offset) override {
    if (bytes == 0) return;
    PM_CUDA_CHECK(cudaMemcpyAsync(dst, static_cast<const char*>(src.handle()) + offset, bytes, cudaMemcpyDeviceToHost, stream_));
    PM_CUDA_CHECK(cudaStreamSynchronize(stream_));
  }

  void fill_zero(DeviceBuffer& dst, size_t bytes) override {
    if (bytes == 0) return;
    PM_CUDA_CHECK(cudaMemsetAsync(dst.handle(), 0, bytes, stream_));
  }

  void copy(const DeviceBuffer& src, DeviceBuffer& dst, size_t bytes) override {
    if (bytes == 0) return;
    PM_CUDA_CHECK(cudaMemcpyAsync(dst.handle(), src.handle(), bytes, cudaMemcpyDeviceToDevice, stream_));
  }

  void launch(KernelId id, uint32_t work_items, const LaunchParams& params) override {
    if (work_items == 0) return;
    void* args[kBufferSlotCount + 2];
    auto slot_values = slots();  // cudaLaunchKernel reads each argument through a pointer to it
    for (size_t i = 0; i < kBufferSlotCount; ++i) args[i] = &slot_values[i];
    LaunchParams params_copy = params;
    uint32_t items = work_items;
    args[kBufferSlotCount] = &params_copy;
    args[kBufferSlotCount + 1] = &items;
    const unsigned block = 128;
    const unsigned grid = (work_items + block - 1) / block;
    cudaError_t err = cudaLaunchKernel(pm_cuda_kernel_table[static_cast<int>(id)], dim3(grid), dim3(block), args, 0, stream_);
    if (err != cudaSuccess)
      throw DeviceError(std::string("CUDA: launching kernel ") + kernel_name(id) + " on " +
                        std::to_string(work_items) + " work items failed with " + cudaGetErrorName(err) + " (" +
                        cudaGetErrorString(err) + ")");
  }

  void sort_pairs(SortBuffers& buffers, uint32_t count, int key_bits) override {
    if (count <= 1) return;
    cub::DoubleBuffer<uint32_t> keys(static_cast<uint32_t*>(buffers.keys.handle()),
                                     static_cast<uint32_t*>(buffers.keys_alt.handle()));
    cub::DoubleBuffer<uint32_t> values(static_cast<uint32_t*>(buffers.values.handle()),
                                       static_cast<uint32_t*>(buffers.values_alt.handle()));
    size_t temp_bytes = 0;
    PM_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(nullptr, temp_bytes, keys, values, int(count), 0, key_bits, stream_));
    if (sort_temp_.bytes() < temp_bytes) sort_temp_ = allocate(temp_bytes, "CUB radix sort temporary storage");
    PM_CUDA_CHECK(cub::DeviceRadixSort::SortPairs(sort_temp_.handle(), temp_bytes, keys, values, int(count), 0,
                                                  key_bits, stream_));
    // CUB picks which half of each double buffer holds the result.
    if (keys.Current() != buffers.keys.handle()) {
      std::swap(buffers.keys, buffers.keys_alt);
      std::swap(buffers.values, buffers.values_alt);
    }
  }

  void synchronize() override { PM_CUDA_CHECK(cudaStreamSynchronize(stream_)); }

  TimerEvent record_timer() override {
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
  DeviceInfo info_;
  cudaStream_t stream_ = nullptr;
  DeviceBuffer sort_temp_;
};

}  // namespace

std::vector<DeviceInfo> list_cuda_devices() {
  std::vector<DeviceInfo> infos;
  int count = cuda_device_count();
  for (int i = 0; i < count; ++i) infos.push_back(describe(i));
  return infos;
}

std::unique_ptr<Device> create_cuda_device(int index) {
  int count = cuda_device_count();
  if (count == 0) throw DeviceError("CUDA: no CUDA device found (no GPU, or no CUDA driver)");
  if (index < 0 || index >= count)
    throw InputError("--device " + std::to_string(index) + ": CUDA has " + std::to_string(count) +
                     " device(s); see 'pmrender devices'");
  return std::make_unique<CudaDevice>(index);
}

}  // namespace pm
