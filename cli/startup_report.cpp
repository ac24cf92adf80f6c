// The start-up table and JSON of bench and render -v (startup_report.h).
#include "cli/startup_report.h"

#include <algorithm>

namespace pm::cli {

namespace {

std::string device_label(const Device& device) {
  return device.info().backend + " " + std::to_string(device.info().index);
}

}  // namespace

StartupSteps::StartupSteps() : last_(process_clock_origin()) {}

void StartupSteps::mark(const std::string& name, const std::string& detail) {
  const StartupClock::time_point now = StartupClock::now();
  steps_.push_back({name, ms_between(last_, now), detail});
  last_ = now;
}

StartupReport make_startup_report(const StartupSteps& host, const std::vector<Device*>& devices,
                                  const std::vector<const Renderer*>& renderers) {
  StartupReport report;
  report.before_origin_ms = process_start_to_origin_ms();
  // The host's steps up to the devices' opening come first, the rest (if any) after the renderer.
  for (const StartupStep& s : host.steps()) report.rows.push_back({"", s});
  report.devices_in_parallel = devices.size() > 1;
  for (const Device* d : devices) {
    for (const StartupStep& s : d->startup().steps) report.rows.push_back({device_label(*d), s});
    if (d->startup().program_cache != ProgramCacheUse::none) {
      std::string use = device_label(*d) + ": " + program_cache_use_name(d->startup().program_cache);
      if (d->startup().cache_entry_rejected) use += " (an unusable entry was replaced)";
      report.program_cache.push_back(use);
    }
  }
  if (!renderers.empty())
    for (const StartupStep& s : renderers.front()->setup_steps()) report.rows.push_back({"renderer", s});
  bool begun = false;
  StartupClock::time_point first{};
  for (const Renderer* r : renderers)
    if (r->has_begun_a_frame() && (!begun || r->first_frame_begun() < first)) {
      first = r->first_frame_begun();
      begun = true;
    }
  if (begun) report.to_first_frame_ms = ms_since_origin(first);
  return report;
}

void print_startup_report(std::FILE* out, const StartupReport& r, double frame_ms, const char* frame_label) {
  std::fprintf(out, "start-up, step by step:\n");
  std::fprintf(out, "  %-34s %10s   %s\n", "step", "ms", "what");
  double sum = 0;
  if (r.before_origin_ms >= 0) {
    std::fprintf(out, "  %-34s %10.1f   %s\n", "before main", r.before_origin_ms,
                 "process start to pmrender's first code: loading shared libraries (10 ms clock ticks)");
    sum += r.before_origin_ms;
  }
  for (const StartupRow& row : r.rows) {
    const std::string name = row.who.empty() ? row.step.name : row.who + ": " + row.step.name;
    std::fprintf(out, "  %-34s %10.1f   %s\n", name.c_str(), row.step.ms, row.step.detail.c_str());
    sum += row.step.ms;
  }
  if (r.to_first_frame_ms >= 0) {
    const double total = r.to_first_frame_ms + std::max(0.0, r.before_origin_ms);
    // Several devices open at once: their rows overlap, so no remainder can be computed.
    if (!r.devices_in_parallel)
      std::fprintf(out, "  %-34s %10.1f   %s\n", "other host work", std::max(0.0, total - sum),
                   "the rest up to the first frame: checks, memory queries, frame set-up");
    std::fprintf(out, "  %-34s %10.1f   %s\n", "to the first frame", total,
                 "process start to the first frame's first launch");
  }
  for (const std::string& use : r.program_cache) std::fprintf(out, "program cache: %s\n", use.c_str());
  if (r.first_frame_wall_ms >= 0) std::fprintf(out, "first frame (host wall): %.1f ms\n", r.first_frame_wall_ms);
  if (frame_ms > 0 && r.to_first_frame_ms >= 0)
    std::fprintf(out, "start-up is %.2f x %s (%.1f ms)\n",
                 (r.to_first_frame_ms + std::max(0.0, r.before_origin_ms)) / frame_ms, frame_label, frame_ms);
}

nlohmann::ordered_json startup_json(const StartupReport& r) {
  using Json = nlohmann::ordered_json;
  Json steps = Json::array();
  for (const StartupRow& row : r.rows)
    steps.push_back({{"who", row.who.empty() ? "process" : row.who},
                     {"step", row.step.name},
                     {"ms", row.step.ms},
                     {"detail", row.step.detail}});
  Json j;
  j["before_main_ms"] = r.before_origin_ms >= 0 ? Json(r.before_origin_ms) : Json(nullptr);
  j["steps"] = steps;
  j["to_first_frame_ms"] =
      r.to_first_frame_ms >= 0 ? Json(r.to_first_frame_ms + std::max(0.0, r.before_origin_ms)) : Json(nullptr);
  j["first_frame_wall_ms"] = r.first_frame_wall_ms >= 0 ? Json(r.first_frame_wall_ms) : Json(nullptr);
  j["program_cache"] = r.program_cache;
  return j;
}

void print_device_startup_messages(const std::vector<Device*>& devices, bool verbose, bool quiet) {
  for (const Device* d : devices) {
    if (!quiet && !d->startup().warning.empty())
      std::fprintf(stderr, "pmrender: warning: %s\n", d->startup().warning.c_str());
    if (verbose)
      for (const std::string& note : d->startup().notes) std::printf("%s: %s\n", device_label(*d).c_str(), note.c_str());
  }
  std::fflush(stdout);
}

}  // namespace pm::cli
