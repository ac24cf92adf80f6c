// Host and device memory for `render`: what is available, a refusal with the numbers when a
// request cannot fit (exit code 2, before the first frame), and what a run used (--verbose).
// PoCL commits an OpenCL buffer only when a kernel first touches it, and aborts on an assertion
// when that fails, so a request that does not fit must be refused before the first frame.
#pragma once

#include <cstdint>
#include <string>

#include "render/device.h"

namespace pm::cli {

// Host memory a process may still take: the least of MemAvailable (/proc/meminfo), the room
// left under RLIMIT_AS (limit minus the address space in use) and under a cgroup v2 memory.max.
struct HostMemory {
  uint64_t available_bytes = UINT64_MAX;
  std::string limited_by;  // "MemAvailable", "RLIMIT_AS (ulimit -v)" or "cgroup memory.max"
};
HostMemory available_host_memory();

// Host memory one frame of width x height needs at its peak: Renderer::read_image holds the four
// layers read back as float4 (64 bytes a pixel) and their RGB copies (48), the EXR writer half
// copies of them (24), the preview 3 bytes: 112 bytes a pixel at the worst moment, counted as 128.
// The extra layers (--layers) add their three float4 buffers (48), their copies (44) and half
// copies (22): another 128.
uint64_t host_frame_bytes(int width, int height, bool extra_layers);

// Refuses (InputError naming --resolution, with the numbers) a frame whose host memory cannot fit.
void check_host_memory_for_frame(int width, int height, bool extra_layers);

// Refuses (InputError, with the numbers) a render whose device buffers, device_bytes in all,
// do not fit: a CUDA device's memory, or, on OpenCL (whose buffers may be host memory, as on
// PoCL, and whose reported capacity is no limit there), the host memory beside the frame's own. Called with the bytes the renderer has
// allocated before its first frame (Device::allocated_bytes()); an estimate made before any
// allocation can be passed the same way.
void check_device_memory(uint64_t device_bytes, const DeviceInfo& device, int width, int height, bool extra_layers);

// Resident set size of this process now and at its peak (VmRSS, VmHWM of /proc/self/status).
uint64_t host_rss_bytes();
uint64_t peak_host_rss_bytes();

// What a run held at one moment, for print_memory_summary.
struct MemorySnapshot {
  uint64_t host_rss_bytes = 0;
  uint64_t device_bytes = 0;
};

// --verbose's last line: host resident memory and device memory held after the first frame
// (`first`) and at the end, with their peaks, so that growth over a sequence shows.
void print_memory_summary(const MemorySnapshot& first, const Device& device);

// "1.5 GiB", "310.2 MiB", "12 KiB".
std::string bytes_text(uint64_t bytes);

}  // namespace pm::cli
