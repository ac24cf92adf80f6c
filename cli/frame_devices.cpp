// Devices, renderer pools and frame jobs of a render (frame_devices.h).
#include "cli/frame_devices.h"

#include <algorithm>
#include <sstream>

#include "cli/memory.h"
#include "render/host_threads.h"
#include "render/errors.h"

namespace pm::cli {

std::vector<int> parse_device_list(const std::string& text) {
  std::vector<int> indices;
  if (text.empty() || text == "all") return indices;
  std::stringstream in(text);
  std::string item;
  while (std::getline(in, item, ',')) {
    size_t used = 0;
    int index = -1;
    try {
      index = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (item.empty() || used != item.size() || index < 0 || item[0] == '+')
      throw InputError("--devices: expected 'all' or device indices like 0,1 (see 'pmrender devices'), got '" + text + "'");
    if (std::find(indices.begin(), indices.end(), index) != indices.end())
      throw InputError("--devices: device " + item + " is listed twice");
    indices.push_back(index);
  }
  if (text.back() == ',') throw InputError("--devices: empty item after the last comma in '" + text + "'");
  return indices;
}

std::vector<Device*> device_pointers(const FrameDevices& opened) {
  std::vector<Device*> all;
  for (const auto& d : opened.devices) all.push_back(d.get());
  return all;
}

std::vector<const Renderer*> renderer_pointers(const FrameDevices& opened) {
  std::vector<const Renderer*> all;
  for (const auto& pool : opened.pools)
    for (size_t i = 0; i < pool->size(); ++i) all.push_back(&pool->renderer(i));
  return all;
}

FrameDevices open_devices(const DeviceChoice& choice, bool sequence, uint32_t checkpoint_every) {
  FrameDevices opened;
  std::vector<std::unique_ptr<Device>>& devices = opened.devices;
  if (!choice.several) devices.push_back(create_device(choice.backend, choice.device));
  else devices = create_devices(choice.backend, choice.indices);
  if (devices.size() > 1 && !sequence && checkpoint_every > 0)
    throw InputError("--checkpoint-every: a single frame on several --devices cannot be checkpointed");
  return opened;
}

void make_frame_jobs(FrameDevices& opened, bool sequence, const Scene& scene, const RenderSettings& settings,
                     const FrameJobOptions& job_options, int width, int height, std::unique_ptr<Renderer> first) {
  std::vector<Device*> all = device_pointers(opened);
  if (sequence) {
    opened.pools.resize(all.size());  // each device's scene upload on its own thread
    for_each_device(all.size(), [&](size_t d) {
      opened.pools[d] = std::make_unique<RendererPool>(std::vector<Device*>{all[d]}, scene, settings,
                                                       d == 0 ? std::move(first) : nullptr);
    });
  } else {
    opened.pools.push_back(std::make_unique<RendererPool>(all, scene, settings, std::move(first)));
  }
  for (auto& d : opened.devices)  // before PoCL commits the buffers: a refusal instead of an abort
    check_device_memory(d->needed_bytes(), d->info(), width, height, !settings.layers.empty());
  for (auto& pool : opened.pools) opened.jobs.push_back(std::make_unique<FrameJob>(*pool, scene, job_options));
}

}  // namespace pm::cli
