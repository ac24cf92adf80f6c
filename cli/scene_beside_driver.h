// The scene's load beside the device driver's start: loading and checking a real scene takes
// hundreds of milliseconds on the host, and so does the driver's initialisation (CUDA: the
// driver and the device's primary context, about 230 ms on an H100; OpenCL: the ICD loader and
// the drivers). Neither needs the other, so the scene loads on a thread while the calling thread
// starts the driver; the device's opening then finds it done (docs/benchmarks.md, "Start-up to
// the first frame").
#pragma once

#include "cli/render_options.h"
#include "cli/startup_report.h"

namespace pm::cli {

// load_scene(o, report) on a thread while this thread starts o.backend's driver (device_index:
// the device to open, -1 when several are). Marks one start-up step, "scene load", whose detail
// says how long each side took. Bad input is reported as load_scene reports it, after the
// driver's start has finished (a driver's initialisation cannot be abandoned midway). Under a
// limited address space (ulimit -v) the scene loads alone and the driver starts with the device,
// after the memory checks.
Scene load_scene_beside_driver(const RenderOptions& o, int device_index, SceneLoadReport* report,
                               StartupSteps* startup);

}  // namespace pm::cli
