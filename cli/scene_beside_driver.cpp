// The scene's load on a thread beside the driver's start (scene_beside_driver.h).
#include "cli/scene_beside_driver.h"

#include <sys/resource.h>

#include <cstdio>
#include <future>

#include "render/device.h"
#include "render/startup_timing.h"

namespace pm::cli {

namespace {

// Whether the process's address space is limited (ulimit -v, as batch systems set it).
bool address_space_limited() {
  rlimit limit{};
  return getrlimit(RLIMIT_AS, &limit) == 0 && limit.rlim_cur != RLIM_INFINITY;
}

}  // namespace

Scene load_scene_beside_driver(const RenderOptions& o, int device_index, SceneLoadReport* report,
                               StartupSteps* startup) {
  // Under a limited address space the driver waits for the device's opening: its mappings count
  // against the limit, and the frame's memory check, made before any device work, must judge the
  // request by what the user has, not by what a driver took first (cli/memory.h).
  if (address_space_limited()) {
    Scene scene = load_scene(o, report);
    startup->mark("scene load", scene.source + " (the driver starts with the device: the address space is limited)");
    return scene;
  }
  double load_ms = 0;
  std::future<Scene> loading = std::async(std::launch::async, [&o, report, &load_ms] {
    StepClock clock;
    Scene scene = load_scene(o, report);
    load_ms = clock.lap_ms();
    return scene;
  });
  // The driver starts on this thread, the process's lasting one (render/device.h says why).
  StepClock clock;
  warm_up_backend(o.backend, device_index);
  const double driver_ms = clock.lap_ms();
  Scene scene = loading.get();  // rethrows the load's error
  char detail[160];
  std::snprintf(detail, sizeof(detail), "%s: %.1f ms; beside it the %s driver's start: %.1f ms", scene.source.c_str(),
                load_ms, o.backend.c_str(), driver_ms);
  startup->mark("scene load", detail);
  return scene;
}

}  // namespace pm::cli
