// A frame's passes shared between devices, one host thread per device.
#include "render/renderer_pool.h"

#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>

#include "render/host_threads.h"
#include "render/errors.h"
#include "render/interruption.h"

namespace pm {

RendererPool::RendererPool(const std::vector<Device*>& devices, const Scene& scene, const RenderSettings& settings)
    : RendererPool(devices, scene, settings, nullptr) {}

RendererPool::RendererPool(const std::vector<Device*>& devices, const Scene& scene, const RenderSettings& settings,
                           std::unique_ptr<Renderer> first) {
  if (devices.empty()) throw InputError("no device to render with");
  renderers_.resize(devices.size());
  renderers_[0] = std::move(first);
  // Each device uploads the scene and allocates on a thread of its own (its BVH build and the
  // uploads overlap those of the others).
  for_each_device(devices.size(), [&](size_t d) {
    if (!renderers_[d]) renderers_[d] = std::make_unique<Renderer>(*devices[d], scene, settings);
  });
}

ProgressiveResult RendererPool::render_progressive(int frame, const PassBudget& budget, const FilmSums* resume,
                                                   double resumed_seconds, const ProgressiveCallbacks& callbacks) {
  if (renderers_.size() == 1) return pm::render_progressive(first(), frame, budget, resume, resumed_seconds, callbacks);
  if (budget.checkpoint_every > 0) throw SettingError("checkpoint-every", "checkpoints need each frame on one device");
  const auto start = std::chrono::steady_clock::now();
  auto seconds = [&] {
    return resumed_seconds + std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  };
  uint32_t cap = budget.max_passes;
  const IndirectMethod* method = first().method();
  if (!method) cap = 0;
  else if (method->max_passes() > 0 && method->max_passes() < cap) cap = method->max_passes();

  // The frame begins on every device (camera pass, film cleared), in parallel, and the first device's
  // film takes the resumed sums before any pass is handed out.
  for_each_device(renderers_.size(), [&](size_t d) { renderers_[d]->begin_frame(frame); });
  if (resume) first().set_film_sums(*resume);
  std::atomic<uint32_t> next_pass{resume ? resume->passes : 0u};
  std::atomic<uint32_t> passes_done{resume ? resume->passes : 0u};
  std::atomic<bool> stop{false};
  std::mutex stop_mutex;
  ProgressiveResult result;
  result.stopped_by = "passes";
  LevelledErrorWatch watch;  // the first device's readings
  std::exception_ptr failure;
  passes_per_device_.assign(renderers_.size(), 0);

  auto work = [&](size_t d) {
    Renderer& r = *renderers_[d];
    try {
      while (!stop) {
        throw_if_interrupted();
        const uint32_t pass = next_pass++;
        if (pass >= cap) break;
        r.run_pass(pass);
        if (budget.open_ended() || d == 0) r.wait();
        ++passes_per_device_[d];
        const uint32_t done = ++passes_done;
        PassReport report;
        report.passes = done;
        report.seconds = seconds();
        if (d == 0 && budget.target_error > 0) {
          // The first device holds passes_per_device_[0] of the frame's passes: the frame's mean
          // has sqrt(done / own passes) less noise (its bias is the same).
          const double own = r.estimate_error(false, std::sqrt(double(r.passes_done()) / double(done)));
          if (own >= 0) report.error = own;
        }
        if (d == 0 && callbacks.after_pass) callbacks.after_pass(report);
        std::lock_guard<std::mutex> lock(stop_mutex);
        if (budget.target_error > 0 && d == 0 && report.error >= 0 && done >= kMinPassesForError &&
            r.last_error_upper() <= budget.target_error) {
          result.stopped_by = "error";
          stop = true;
        }
        if (budget.target_error > 0 && d == 0 && !stop &&
            watch.levelled(done, report.seconds, report.error, r.last_error_upper(), budget.target_error)) {
          result.stopped_by = "levelled";
          stop = true;
        }
        if (budget.seconds > 0 && report.seconds >= budget.seconds && !stop) {
          result.stopped_by = "time";
          stop = true;
        }
      }
      r.wait();
    } catch (...) {
      std::lock_guard<std::mutex> lock(stop_mutex);
      if (!failure) failure = std::current_exception();
      stop = true;
    }
  };
  std::vector<std::thread> threads;
  for (size_t d = 1; d < renderers_.size(); ++d) threads.emplace_back(work, d);
  work(0);
  for (std::thread& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);

  // The other devices' passes added into the first device's film, in device order.
  for (size_t d = 1; d < renderers_.size(); ++d)
    if (renderers_[d]->passes_done() > 0) first().add_film_sums(renderers_[d]->film_sums());
  first().wait();
  result.passes = first().passes_done();
  result.error = first().estimate_error(true);
  result.seconds = seconds();
  return result;
}

}  // namespace pm
