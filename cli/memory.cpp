// Host memory probes (/proc, getrlimit, cgroup v2) and the memory refusals of `render`
// (memory.h).
#include "cli/memory.h"

#include <sys/resource.h>
#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <sstream>

#include "render/errors.h"

namespace pm::cli {

namespace {

// The value of a "Key:   123 kB" line of a /proc file, in bytes; 0 when absent.
uint64_t proc_kb_field(const char* file, const std::string& key) {
  std::ifstream in(file);
  std::string line;
  while (std::getline(in, line)) {
    if (line.compare(0, key.size() + 1, key + ":") != 0) continue;
    std::istringstream fields(line.substr(key.size() + 1));
    uint64_t kb = 0;
    fields >> kb;
    return kb * 1024;
  }
  return 0;
}

uint64_t cgroup_room() {
  std::ifstream max_file("/sys/fs/cgroup/memory.max"), current_file("/sys/fs/cgroup/memory.current");
  std::string max_text;
  uint64_t current = 0;
  if (!(max_file >> max_text) || max_text == "max" || !(current_file >> current)) return UINT64_MAX;
  const uint64_t limit = std::stoull(max_text);
  return limit > current ? limit - current : 0;
}

}  // namespace

HostMemory available_host_memory() {
  HostMemory memory;
  const uint64_t available = proc_kb_field("/proc/meminfo", "MemAvailable");
  if (available > 0) {
    memory.available_bytes = available;
    memory.limited_by = "MemAvailable";
  }
  struct rlimit limit;
  if (::getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY) {
    const uint64_t used = proc_kb_field("/proc/self/status", "VmSize");
    const uint64_t room = limit.rlim_cur > used ? uint64_t(limit.rlim_cur) - used : 0;
    if (room < memory.available_bytes) {
      memory.available_bytes = room;
      memory.limited_by = "RLIMIT_AS (ulimit -v)";
    }
  }
  const uint64_t cgroup = cgroup_room();
  if (cgroup < memory.available_bytes) {
    memory.available_bytes = cgroup;
    memory.limited_by = "cgroup memory.max";
  }
  return memory;
}

uint64_t host_frame_bytes(int width, int height, bool extra_layers) {
  return uint64_t(width) * uint64_t(height) * (extra_layers ? 256 : 128);
}

void check_host_memory_for_frame(int width, int height, bool extra_layers) {
  const uint64_t needed = host_frame_bytes(width, height, extra_layers);
  const HostMemory host = available_host_memory();
  if (needed <= host.available_bytes) return;
  throw InputError("--resolution " + std::to_string(width) + "x" + std::to_string(height) + ": a frame needs about " +
                   bytes_text(needed) + " of host memory, but " + bytes_text(host.available_bytes) +
                   " are available (" + host.limited_by + ")");
}

void check_device_memory(uint64_t device_bytes, const DeviceInfo& device, int width, int height, bool extra_layers) {
  const std::string what = "the render needs " + bytes_text(device_bytes) + " of device memory";
  if (!device.buffers_in_host_memory) {
    if (device.memory_bytes > 0 && device_bytes > device.memory_bytes)
      throw InputError(what + ", but " + device.name + " has " + bytes_text(device.memory_bytes) +
                       "; lower --resolution or --photons");
    return;
  }
  // A CPU device's reported global memory is no limit (PoCL 3.1 reports 4.7 GiB on a 23 GiB
  // machine and allocates beyond it): its buffers are host memory.
  const uint64_t needed = device_bytes + host_frame_bytes(width, height, extra_layers);
  const HostMemory host = available_host_memory();
  if (needed > host.available_bytes)
    throw InputError(what + " and " + bytes_text(host_frame_bytes(width, height, extra_layers)) + " for the frame on the host; " +
                     "the buffers of " + device.name + " are host memory, where " + bytes_text(host.available_bytes) +
                     " are available (" + host.limited_by + "); lower --resolution or --photons");
}

uint64_t host_rss_bytes() { return proc_kb_field("/proc/self/status", "VmRSS"); }
uint64_t peak_host_rss_bytes() { return proc_kb_field("/proc/self/status", "VmHWM"); }

void print_memory_summary(const MemorySnapshot& first, const Device& device) {
  std::printf("memory: host %s after the first frame, %s at the end (peak %s); device %s after the first frame, %s at "
              "the end (peak %s)\n",
              bytes_text(first.host_rss_bytes).c_str(), bytes_text(host_rss_bytes()).c_str(),
              bytes_text(peak_host_rss_bytes()).c_str(), bytes_text(first.device_bytes).c_str(),
              bytes_text(device.allocated_bytes()).c_str(), bytes_text(device.peak_allocated_bytes()).c_str());
}

std::string bytes_text(uint64_t bytes) {
  char text[32];
  if (bytes >= (uint64_t(1) << 30)) std::snprintf(text, sizeof(text), "%.1f GiB", double(bytes) / double(1u << 30));
  else if (bytes >= (uint64_t(1) << 20)) std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / double(1u << 20));
  else std::snprintf(text, sizeof(text), "%.0f KiB", double(bytes) / 1024.0);
  return text;
}

}  // namespace pm::cli
