// `pmrender devices`: every device of every compiled-in backend, with the index --device takes.
#include <cstdio>

#include "cli/commands.h"
#include "render/device.h"

namespace pm::cli {

Run add_devices_command(CLI::App& app) {
  app.add_subcommand("devices", "List the CUDA and OpenCL devices pmrender can use");
  return [] {
    std::vector<DeviceInfo> devices = list_devices();
    std::string backends;
    for (const std::string& b : compiled_backends()) backends += (backends.empty() ? "" : ", ") + b;
    std::printf("backends compiled in: %s\n", backends.c_str());
    if (devices.empty()) {
      std::printf("no devices found\n");
      return 1;
    }
    for (const DeviceInfo& d : devices) {
      std::printf("%-7s --device %d  %s  [%s; driver %s; %.1f GiB%s; %d compute units]\n", d.backend.c_str(), d.index,
                  d.name.c_str(), d.platform.c_str(), d.driver.c_str(), double(d.memory_bytes) / (1u << 30),
                  d.buffers_in_host_memory ? " (host memory)" : "", d.compute_units);
    }
    return 0;
  };
}

}  // namespace pm::cli
