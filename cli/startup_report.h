// Start-up of `pmrender bench` and `pmrender render -v`, step by step, beside the frame: the
// process before main, options and scene load, each device's opening (context, program build or
// program cache load, kernels; CUDA: driver, context, module load), the renderer's set-up (BVH
// build, textures, scene upload, buffers, the method) and the time from the process's start to
// its first frame. Also the device's start-up messages: the program cache's warning (shown
// unless quiet) and notes (verbose only).
#pragma once

#include <cstdio>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "render/device.h"
#include "render/renderer.h"
#include "render/startup_timing.h"

namespace pm::cli {

struct StartupRow {
  std::string who;  // "" for the process, else the device ("opencl 0") or "renderer"
  StartupStep step;
};

struct StartupReport {
  double before_origin_ms = -1;  // process creation to the library's static initialisation
  std::vector<StartupRow> rows;  // in the order they ran
  double to_first_frame_ms = -1;  // process clock origin to the first frame's first launch
  double first_frame_wall_ms = -1;  // that frame's host wall time, where known
  bool devices_in_parallel = false;  // several devices opened at once: rows overlap in time
  std::vector<std::string> program_cache;  // per device: what the program cache did
};

// Times the host's own steps of a command, from the process clock origin on: the first mark is
// everything before the command ran (options), later marks each step since the previous one.
class StartupSteps {
 public:
  StartupSteps();
  // The time since the previous mark as a step of the process.
  void mark(const std::string& name, const std::string& detail = "");
  const std::vector<StartupStep>& steps() const { return steps_; }

 private:
  StartupClock::time_point last_;
  std::vector<StartupStep> steps_;
};

// The report of a run: the host's steps, every device's opening and the first renderer's set-up;
// the first frame is the earliest any of the renderers began.
StartupReport make_startup_report(const StartupSteps& host, const std::vector<Device*>& devices,
                                  const std::vector<const Renderer*>& renderers);

// The table; frame_ms (the frame beside it, e.g. a measured frame's median) may be negative.
void print_startup_report(std::FILE* out, const StartupReport& report, double frame_ms, const char* frame_label);
nlohmann::ordered_json startup_json(const StartupReport& report);

// The devices' start-up warnings on stderr unless quiet (at most one per process, see
// DeviceStartup::warning) and, when verbose, their notes on stdout.
void print_device_startup_messages(const std::vector<Device*>& devices, bool verbose, bool quiet);

}  // namespace pm::cli
