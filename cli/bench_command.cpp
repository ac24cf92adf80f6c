// `pmrender bench [SCENE]`: renders frames without writing images and reports per-stage device
// times, host wall time per frame, the method's statistics and peak device memory, as one table
// and optionally as JSON. Method-independent: the stages and statistics are whatever the
// renderer's method reports. The photon-mapping extras (--leaf-sweep, --radius-histogram) live
// in cli/bench_photon.cpp.
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "cli/bench_measure.h"
#include "cli/bench_photon.h"
#include "cli/commands.h"
#include "cli/render_options.h"
#include "cli/scene_beside_driver.h"
#include "cli/startup_report.h"
#include "render/atomic_file.h"
#include "render/device.h"
#include "render/errors.h"
#include "render/renderer.h"
#include "scene_io/frame_spec.h"

namespace pm::cli {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// The scene is static for now: any frame number in this range is a valid (reseeded) frame.
constexpr int kLastFrame = 100000;

struct BenchOptions {
  RenderOptions render;
  std::string frames;
  int warmup = 2;
  int repeat = 10;
  std::string json;
  std::string leaf_sweep;
  bool radius_histogram = false;
  CLI::Option* repeat_option = nullptr;
};

FramePlan plan_frames(const BenchOptions& o) {
  if (o.warmup < 0 || o.warmup > kLastFrame)
    throw InputError("--warmup: expected 0 to " + std::to_string(kLastFrame) + " frames, got " + std::to_string(o.warmup));
  FramePlan plan;
  if (!o.frames.empty()) {
    if (o.repeat_option && o.repeat_option->count() > 0)
      throw InputError("--repeat: cannot be combined with --frames (the frame list is the measured frames)");
    plan.measured = parse_frames_option(o.frames, 0, kLastFrame);
    for (int i = 0; i < o.warmup; ++i) plan.warmup.push_back(plan.measured[size_t(i) % plan.measured.size()]);
    return plan;
  }
  if (o.repeat < 1) throw InputError("--repeat: expected at least 1 measured frame, got " + std::to_string(o.repeat));
  if (int64_t(o.warmup) + o.repeat - 1 > kLastFrame)
    throw InputError("--repeat: warmup and measured frames must fit in frames 0-" + std::to_string(kLastFrame));
  for (int f = 0; f < o.warmup; ++f) plan.warmup.push_back(f);
  for (int f = o.warmup; f < o.warmup + o.repeat; ++f) plan.measured.push_back(f);
  return plan;
}

void check_json_path(const std::string& path) {
  if (path.empty()) throw InputError("--json: empty file name");
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw InputError("--json: '" + path + "' is a directory");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) throw InputError("--json: directory '" + dir.string() + "' does not exist");
}

std::string utc_now() {
  std::time_t t = std::time(nullptr);
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

// "12.3 M" style: value scaled to k, M, G, T with three significant digits.
std::string si(double v) {
  const char* prefixes[] = {"", "k", "M", "G", "T"};
  int i = 0;
  while (std::fabs(v) >= 1000.0 && i < 4) {
    v /= 1000.0;
    ++i;
  }
  char buf[32];
  std::snprintf(buf, sizeof(buf), v >= 100 ? "%.0f %s" : v >= 10 ? "%.1f %s" : "%.2f %s", v, prefixes[i]);
  return buf;
}

Json spread_json(const Spread& s) { return Json{{"median", s.median}, {"min", s.min}, {"max", s.max}}; }

// The "key=value" words of a settings description as JSON fields, numbers where they are numbers.
void add_described_settings(Json& j, const std::string& describe) {
  std::istringstream words(describe);
  std::string word;
  while (words >> word) {
    const size_t eq = word.find('=');
    if (eq == std::string::npos || eq == 0) continue;
    const std::string key = word.substr(0, eq), value = word.substr(eq + 1);
    char* end = nullptr;
    const double number = std::strtod(value.c_str(), &end);
    j[key] = (!value.empty() && end && *end == '\0' && std::isfinite(number)) ? Json(number) : Json(value);
  }
}

struct StageRow {
  StageInfo info;
  Spread ms;
};

int run_bench(const BenchOptions& o) {
  StartupSteps startup;
  // Everything the user can get wrong is checked before the device is opened.
  const FramePlan plan = plan_frames(o);
  if (!o.json.empty()) check_json_path(o.json);
  std::vector<int> sweep;
  if (!o.leaf_sweep.empty()) sweep = parse_leaf_sweep(o.leaf_sweep);
  const RenderSettings settings = render_settings(o.render);
  check_photon_extras(settings, !sweep.empty(), o.radius_histogram);
  startup.mark("options");
  const Scene scene = load_scene_beside_driver(o.render, o.render.device, nullptr, &startup);

  std::unique_ptr<Device> device = create_device(o.render.backend, o.render.device);
  print_device_startup_messages({device.get()}, false, false);
  const DeviceInfo info = device->info();
  device->reset_peak();
  auto renderer = std::make_unique<Renderer>(*device, scene, settings);
  StageTimer timer(*device);
  const std::string describe = renderer->describe();

  std::printf("pmrender bench: %s (%s), %d triangles, %zu light(s)\n", scene.name.c_str(), scene.source.c_str(),
              int(scene.triangle_count()), scene.lights.size());
  std::printf("device: %s --device %d: %s [%s; driver %s]\n", info.backend.c_str(), info.index, info.name.c_str(),
              info.platform.c_str(), info.driver.c_str());
  std::printf("settings: %s\n", describe.c_str());
  uint64_t texels = 0;
  for (const TextureImage& image : scene.images) texels += uint64_t(image.width) * uint64_t(image.height);
  const uint64_t texture_bytes = renderer->texture_bytes();
  if (scene.has_textures())
    std::printf("textures: %zu images, %.0f texels, %.1f MiB on the device (texels, descriptors, texture coordinates, sRGB table)\n",
                scene.images.size(), double(texels), double(texture_bytes) / (1024.0 * 1024.0));
  std::printf("frames: %zu warmup, %zu measured (%d-%d%s)\n\n", plan.warmup.size(), plan.measured.size(),
              plan.measured.front(), plan.measured.back(), o.frames.empty() ? "" : ", from --frames");
  std::fflush(stdout);

  const Measurement base = measure(*renderer, timer, plan, "bench " + scene.name);
  StartupReport startup_report = make_startup_report(startup, {device.get()}, {renderer.get()});
  startup_report.first_frame_wall_ms = base.first_frame_wall_ms;

  // The method's work counters (e.g. photons per gather) on one extra frame, the last measured
  // one again, untimed: counting costs atomics.
  FrameStats counted;
  renderer->set_collect_stats(true);
  renderer->render(base.frames.back(), &counted);
  renderer->set_collect_stats(false);
  const uint64_t peak = device->peak_allocated_bytes();

  // Stage rows in the renderer's order, then any stage that ran without being listed.
  std::vector<StageRow> rows;
  for (const StageInfo& s : renderer->stages()) rows.push_back({s, base.stage(s.name)});
  for (const StageTime& t : base.stages.front()) {
    bool listed = false;
    for (const StageRow& r : rows) listed |= r.info.name == t.stage;
    if (!listed) rows.push_back({StageInfo{t.stage, 0, "", ""}, base.stage(t.stage)});
  }
  double median_sum = 0;
  for (const StageRow& r : rows) median_sum += r.ms.median;

  std::printf("%-22s %10s %10s %10s %7s   %s\n", "stage", "median ms", "min ms", "max ms", "share", "throughput");
  for (const StageRow& r : rows) {
    const double share = median_sum > 0 ? 100.0 * r.ms.median / median_sum : 0.0;
    std::string tp = "-";
    if (r.ms.median > 0 && r.info.work_per_frame > 0) tp = si(r.info.work_per_frame / (r.ms.median / 1000.0)) + r.info.unit;
    std::printf("%-22s %10.3f %10.3f %10.3f %6.1f%%   %s\n", r.info.name.c_str(), r.ms.median, r.ms.min, r.ms.max,
                share, tp.c_str());
  }
  const Spread total = base.total(), wall = base.wall();
  std::printf("%-22s %10.3f %10.3f %10.3f\n", "frame (sum of stages)", total.median, total.min, total.max);
  std::printf("%-22s %10.3f %10.3f %10.3f\n", "frame (host wall)", wall.median, wall.min, wall.max);
  std::printf("frames per second: %.2f (host wall), %.2f (sum of stages)\n", base.fps(), base.fps_stages());
  print_startup_report(stdout, startup_report, wall.median, "a measured frame's median host wall");
  // What each throughput counts, stages with the same meaning on one line.
  for (size_t i = 0; i < rows.size(); ++i) {
    if (rows[i].info.counts.empty()) continue;
    bool seen = false;
    for (size_t k = 0; k < i; ++k) seen |= rows[k].info.counts == rows[i].info.counts;
    if (seen) continue;
    std::string names;
    for (size_t k = i; k < rows.size(); ++k)
      if (rows[k].info.counts == rows[i].info.counts) names += (names.empty() ? "" : ", ") + rows[k].info.name;
    std::printf("throughput of %s: %s\n", names.c_str(), rows[i].info.counts.c_str());
  }

  const uint32_t passes = base.stats.back().passes;
  MethodWork work;
  if (renderer->method()) {
    work = renderer->method()->work(passes);
    std::printf("passes per frame: %u, %.0f %ss per frame, at most %.0f a pass\n", passes, work.total,
                work.unit.c_str(), work.largest_pass);
    std::printf("method statistics, median over the measured frames (min-max):\n");
    for (const MethodStats::Entry& e : base.stats.back().method.entries) {
      const Spread s = base.stat(e.name);
      std::printf("  %-22s %.6g (%.6g-%.6g)\n", e.name.c_str(), s.median, s.min, s.max);
    }
    std::printf("counted in frame %d again (with work counters):", base.frames.back());
    for (const MethodStats::Entry& e : counted.method.entries) std::printf(" %s=%.6g", e.name.c_str(), e.value);
    std::printf("\n");
  } else {
    std::printf("no indirect-light method (direct light only)\n");
  }
  std::printf("peak device memory: %.1f MiB", double(peak) / (1024.0 * 1024.0));
  // Per unit of the largest pass: the memory is sized by one pass, never by the frame's.
  if (work.largest_pass > 0)
    std::printf(", %.0f bytes per %s (%.0f %ss in the largest pass)", double(peak) / work.largest_pass,
                work.unit.c_str(), work.largest_pass, work.unit.c_str());
  std::printf("\n");

  Json histogram, leaf;
  if (o.radius_histogram) histogram = print_radius_histogram(*device, *renderer, base.frames.back());
  std::fflush(stdout);
  if (!sweep.empty()) {
    renderer.reset();
    leaf = run_leaf_sweep(*device, scene, settings, plan, sweep);
  }

  if (!o.json.empty()) {
    Json j;
    j["pmrender_version"] = PMRENDER_VERSION;
    j["date"] = utc_now();
    j["scene"] = {{"name", scene.name},
                  {"source", scene.source},
                  {"triangles", scene.triangle_count()},
                  {"lights", scene.lights.size()},
                  {"texture_images", scene.images.size()},
                  {"texels", texels}};
    Json s = {{"describe", describe},
              {"width", settings.width > 0 ? settings.width : scene.camera.width},
              {"height", settings.height > 0 ? settings.height : scene.camera.height},
              {"method", settings.method ? settings.method->method_name() : "none"}};
    add_described_settings(s, describe);
    j["settings"] = s;
    j["device"] = {{"backend", info.backend},   {"index", info.index},
                   {"name", info.name},         {"platform", info.platform},
                   {"driver", info.driver},     {"memory_bytes", info.memory_bytes},
                   {"compute_units", info.compute_units}};
    j["frames"] = {{"warmup", plan.warmup}, {"measured", plan.measured}};
    Json stage_list = Json::array();
    for (const StageRow& r : rows) {
      Json row = {{"stage", r.info.name},
                  {"median_ms", r.ms.median},
                  {"min_ms", r.ms.min},
                  {"max_ms", r.ms.max},
                  {"share", median_sum > 0 ? r.ms.median / median_sum : 0.0}};
      if (r.ms.median > 0 && r.info.work_per_frame > 0)
        row["throughput"] = {{"per_second", r.info.work_per_frame / (r.ms.median / 1000.0)},
                             {"unit", r.info.unit},
                             {"per_frame", r.info.work_per_frame},
                             {"counts", r.info.counts}};
      stage_list.push_back(row);
    }
    j["stages"] = stage_list;
    j["frame_ms"] = {{"sum_of_stages", spread_json(total)}, {"host_wall", spread_json(wall)}};
    j["fps"] = {{"host_wall", base.fps()}, {"sum_of_stages", base.fps_stages()}};
    j["startup"] = startup_json(startup_report);
    j["work"] = {{"unit", work.unit}, {"per_pass", work.largest_pass}, {"passes", passes}, {"per_frame", work.total}};
    Json method_stats = Json::object();
    for (const MethodStats::Entry& e : base.stats.back().method.entries) method_stats[e.name] = spread_json(base.stat(e.name));
    j["method_stats"] = method_stats;
    Json counted_stats = Json::object();
    for (const MethodStats::Entry& e : counted.method.entries) counted_stats[e.name] = e.value;
    j["counted"] = {{"frame", base.frames.back()}, {"stats", counted_stats}};
    j["memory"] = {{"peak_bytes", peak},
                   {"texture_bytes", texture_bytes},
                   {"unit", work.unit},
                   {"bytes_per_unit", work.largest_pass > 0 ? Json(double(peak) / work.largest_pass) : Json(nullptr)}};
    Json per_frame = Json::array();
    for (size_t i = 0; i < base.frames.size(); ++i) {
      Json stage_ms = Json::object();
      for (const StageTime& t : base.stages[i]) stage_ms[t.stage] = t.ms;
      Json stats = Json::object();
      for (const MethodStats::Entry& e : base.stats[i].method.entries) stats[e.name] = e.value;
      per_frame.push_back({{"frame", base.frames[i]},
                           {"host_wall_ms", base.wall_ms[i]},
                           {"render_ms", base.stats[i].render_ms},
                           {"sum_of_stages_ms", base.stages_total_ms[i]},
                           {"stages_ms", stage_ms},
                           {"stats", stats}});
    }
    j["per_frame"] = per_frame;
    if (o.radius_histogram) j["radius_histogram"] = histogram;
    if (!sweep.empty()) j["leaf_sweep"] = leaf;
    write_file_atomically(o.json, j.dump(2) + "\n");
    std::printf("\nwrote %s\n", o.json.c_str());
  }
  return 0;
}

}  // namespace

Run add_bench_command(CLI::App& app) {
  auto options = std::make_shared<BenchOptions>();
  CLI::App* cmd = app.add_subcommand(
      "bench", "Time every stage of a frame without writing images (default scene: the built-in Cornell box)");
  add_render_options(cmd, options->render);
  cmd->add_option("--frames", options->frames,
                  "Measured frames, e.g. 0-99 or 1,5,10-20:2 (0-100000; replaces --repeat); default: the "
                  "--repeat frames after the warmup frames 0,1,...");
  cmd->add_option("--warmup", options->warmup, "Frames rendered first and not measured")->capture_default_str();
  options->repeat_option =
      cmd->add_option("--repeat", options->repeat, "Measured frames (numbered after the warmup frames)")
          ->capture_default_str();
  cmd->add_option("--json", options->json, "Also write the results as JSON to this file");
  cmd->add_option("--leaf-sweep", options->leaf_sweep,
                  "Measure again per fixed leaf threshold T (e.g. 1,2,4,...,512) and with auto (paper Table 1)");
  cmd->add_flag("--radius-histogram", options->radius_histogram,
                "Print the footprint radii of the last frame in the paper's Table 3 bins (--estimator pd)");
  return [options] { return run_bench(*options); };
}

}  // namespace pm::cli
