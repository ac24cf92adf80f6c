// Timed runs of a renderer over a frame plan, and their medians.
#include "cli/bench_measure.h"

#include <algorithm>
#include <chrono>

#include "cli/progress_line.h"

namespace pm::cli {

Spread spread(std::vector<double> v) {
  Spread s;
  if (v.empty()) return s;
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  s.median = n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
  s.min = v.front();
  s.max = v.back();
  return s;
}

Spread Measurement::stage(const std::string& name) const {
  std::vector<double> v;
  for (const std::vector<StageTime>& frame : stages) {
    double ms = 0;
    for (const StageTime& t : frame)
      if (t.stage == name) ms += t.ms;
    v.push_back(ms);
  }
  return spread(v);
}

Spread Measurement::stat(const std::string& name) const {
  std::vector<double> v;
  for (const FrameStats& s : stats) v.push_back(s.method.get(name));
  return spread(v);
}

double Measurement::fps() const {
  const double ms = wall().median;
  return ms > 0 ? 1000.0 / ms : 0.0;
}

double Measurement::fps_stages() const {
  const double ms = total().median;
  return ms > 0 ? 1000.0 / ms : 0.0;
}

Measurement measure(Renderer& renderer, StageTimer& timer, const FramePlan& plan, const std::string& what) {
  Measurement m;
  renderer.set_stage_timer(&timer);
  renderer.set_collect_stats(false);
  ProgressLine progress(true);
  const size_t total = plan.warmup.size() + plan.measured.size();
  size_t done = 0;
  const auto start = std::chrono::steady_clock::now();
  auto show = [&] {
    progress.show_count(what, done, total,
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), "frame");
  };
  for (int frame : plan.warmup) {
    const auto frame_start = std::chrono::steady_clock::now();
    renderer.render(frame);
    if (m.first_frame_wall_ms < 0)
      m.first_frame_wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - frame_start).count();
    timer.collect();
    ++done;
    show();
  }
  for (int frame : plan.measured) {
    FrameStats stats;
    const auto frame_start = std::chrono::steady_clock::now();
    renderer.render(frame, &stats);
    const auto frame_end = std::chrono::steady_clock::now();
    std::vector<StageTime> times = timer.collect();
    double sum = 0;
    for (const StageTime& t : times) sum += t.ms;
    m.frames.push_back(frame);
    m.stages.push_back(std::move(times));
    m.stages_total_ms.push_back(sum);
    m.wall_ms.push_back(std::chrono::duration<double, std::milli>(frame_end - frame_start).count());
    if (m.first_frame_wall_ms < 0) m.first_frame_wall_ms = m.wall_ms.back();
    m.stats.push_back(std::move(stats));
    ++done;
    show();
  }
  renderer.set_stage_timer(nullptr);
  return m;
}

Measurement measure_with(Device& device, const Scene& scene, const RenderSettings& settings, const FramePlan& plan,
                         const std::string& what) {
  Renderer renderer(device, scene, settings);
  StageTimer timer(device);
  return measure(renderer, timer, plan, what);
}

}  // namespace pm::cli
