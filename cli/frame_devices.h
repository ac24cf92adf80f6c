// The devices of `pmrender render` and what runs on them. With several devices (--devices), a
// single frame shares its passes between them (one RendererPool over all); in a sequence each
// device renders frames of its own (one pool per device, frames handed out by
// render/frame_runs.h), starting on a contiguous run so that camera-only runs keep their photon
// reuse on one device.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "cli/frame_job.h"
#include "render/device.h"
#include "render/renderer_pool.h"

namespace pm::cli {

// "--devices 0,2" -> {0, 2}; "all" -> {} (every device of the backend). InputError otherwise.
std::vector<int> parse_device_list(const std::string& text);

struct DeviceChoice {
  std::string backend;      // --backend
  int device = 0;           // --device, without --devices
  bool several = false;     // --devices given
  std::vector<int> indices; // its list (empty: all)
};

struct FrameDevices {
  std::vector<std::unique_ptr<Device>> devices;
  std::vector<std::unique_ptr<RendererPool>> pools;
  std::vector<std::unique_ptr<FrameJob>> jobs;  // one per pool
};

// The opened devices and every renderer of every pool, for start-up reports.
std::vector<Device*> device_pointers(const FrameDevices& opened);
std::vector<const Renderer*> renderer_pointers(const FrameDevices& opened);

// Opens the devices (each on its own thread, render/host_threads.h); nothing runs on them yet.
FrameDevices open_devices(const DeviceChoice& choice, bool sequence, uint32_t checkpoint_every);

// Uploads the scene to each opened device, checks each device's memory for a frame of width x
// height, and makes the frame jobs. first: a renderer already made on the first device with
// these settings (--method auto's race winner), which the first pool takes over.
void make_frame_jobs(FrameDevices& opened, bool sequence, const Scene& scene, const RenderSettings& settings,
                     const FrameJobOptions& job_options, int width, int height, std::unique_ptr<Renderer> first = nullptr);

}  // namespace pm::cli
