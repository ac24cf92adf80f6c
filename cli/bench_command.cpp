// `pmrender bench [SCENE]`: renders frames without writing images and reports per-stage device
// times (StageTimer), host wall time per frame, photon counts, the paper's k_PD and peak device
// memory, as one table and optionally as JSON. --leaf-sweep reproduces the paper's Table 1 (frame
// rate per photon-map leaf threshold T), --radius-histogram its Table 3 (footprint radii).
#include <unistd.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "animations/frame_spec.h"
#include "cli/commands.h"
#include "cli/render_options.h"
#include "render/device.h"
#include "render/errors.h"
#include "render/renderer.h"
#include "render/stage_timer.h"

namespace pm::cli {

namespace {

namespace fs = std::filesystem;
using Json = nlohmann::ordered_json;

// The scene is static for now: any frame number in this range is a valid (reseeded) frame.
constexpr int kLastFrame = 100000;
// Table 3 of the paper: 0.05-wide bins from 0 to 1.00, then "> 1.00".
constexpr int kRadiusBins = 20;
constexpr double kRadiusBinWidth = 0.05;

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

struct FramePlan {
  std::vector<int> warmup, measured;
};

struct Spread {
  double median = 0, min = 0, max = 0;
};

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

// One timed run over a frame plan with one Renderer.
struct Measurement {
  std::vector<int> frames;
  std::vector<std::array<double, kStageCount>> stage_ms;  // per measured frame
  std::vector<double> stages_total_ms, wall_ms, render_ms;
  std::vector<double> hits, leaf_threshold;
  int batches = 0;

  Spread stage(size_t s) const {
    std::vector<double> v;
    for (const auto& f : stage_ms) v.push_back(f[s]);
    return spread(v);
  }
  Spread total() const { return spread(stages_total_ms); }
  Spread wall() const { return spread(wall_ms); }
  double fps() const {  // host wall
    double ms = wall().median;
    return ms > 0 ? 1000.0 / ms : 0.0;
  }
  double fps_stages() const {  // device time only
    double ms = total().median;
    return ms > 0 ? 1000.0 / ms : 0.0;
  }
};

FramePlan plan_frames(const BenchOptions& o) {
  if (o.warmup < 0 || o.warmup > kLastFrame)
    throw InputError("--warmup: expected 0 to " + std::to_string(kLastFrame) + " frames, got " + std::to_string(o.warmup));
  FramePlan plan;
  if (!o.frames.empty()) {
    if (o.repeat_option && o.repeat_option->count() > 0)
      throw InputError("--repeat: cannot be combined with --frames (the frame list is the measured frames)");
    plan.measured = parse_frame_spec(o.frames, 0, kLastFrame);
    for (int i = 0; i < o.warmup; ++i) plan.warmup.push_back(plan.measured[size_t(i) % plan.measured.size()]);
    return plan;
  }
  if (o.repeat < 1)
    throw InputError("--repeat: expected at least 1 measured frame, got " + std::to_string(o.repeat));
  if (int64_t(o.warmup) + o.repeat - 1 > kLastFrame)
    throw InputError("--repeat: warmup and measured frames must fit in frames 0-" + std::to_string(kLastFrame));
  for (int f = 0; f < o.warmup; ++f) plan.warmup.push_back(f);
  for (int f = o.warmup; f < o.warmup + o.repeat; ++f) plan.measured.push_back(f);
  return plan;
}

std::vector<int> parse_leaf_sweep(const std::string& text) {
  std::vector<int> values;
  std::set<int> seen;
  std::stringstream in(text);
  std::string item;
  if (text.empty()) throw InputError("--leaf-sweep: expected a comma-separated list of thresholds, e.g. 1,2,4,8");
  while (std::getline(in, item, ',')) {
    if (item.empty()) throw InputError("--leaf-sweep: empty item between commas in '" + text + "'");
    size_t used = 0;
    int t = 0;
    try {
      t = std::stoi(item, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used != item.size() || t < 1)
      throw InputError("--leaf-sweep: '" + item + "' is not a positive integer leaf threshold");
    if (seen.insert(t).second) values.push_back(t);
  }
  if (!text.empty() && text.back() == ',') throw InputError("--leaf-sweep: empty item after the last comma");
  return values;
}

void check_json_path(const std::string& path) {
  if (path.empty()) throw InputError("--json: empty file name");
  const fs::path p(path);
  std::error_code ec;
  if (fs::is_directory(p, ec)) throw InputError("--json: '" + path + "' is a directory");
  const fs::path dir = p.has_parent_path() ? p.parent_path() : fs::path(".");
  if (!fs::is_directory(dir, ec)) throw InputError("--json: directory '" + dir.string() + "' does not exist");
}

// Writes text to path through a temporary file in the same folder and a rename, so a reader
// never sees a half-written file.
void write_atomically(const std::string& path, const std::string& text) {
  const std::string tmp = path + ".tmp-" + std::to_string(::getpid());
  {
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    out << text;
    out.flush();
    if (!out) {
      std::error_code ec;
      fs::remove(tmp, ec);
      throw std::runtime_error("--json: cannot write '" + tmp + "'");
    }
  }
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    std::error_code ignored;
    fs::remove(tmp, ignored);
    throw std::runtime_error("--json: cannot rename '" + tmp + "' to '" + path + "': " + ec.message());
  }
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

const char* estimator_name(int e) {
  return e == PM_ESTIMATOR_KNN ? "knn" : e == PM_ESTIMATOR_RADIUS ? "radius" : "pd";
}

class ProgressLine {
 public:
  explicit ProgressLine(std::string what) : what_(std::move(what)), enabled_(::isatty(2)) {}
  void show(size_t done, size_t total) const {
    if (enabled_) std::fprintf(stderr, "\r%s: frame %zu/%zu ", what_.c_str(), done + 1, total);
  }
  ~ProgressLine() {
    if (enabled_) std::fprintf(stderr, "\r%*s\r", int(what_.size()) + 32, "");
  }

 private:
  std::string what_;
  bool enabled_;
};

Measurement measure(Renderer& renderer, StageTimer& timer, const FramePlan& plan, const std::string& what) {
  Measurement m;
  renderer.set_stage_timer(&timer);
  renderer.set_collect_stats(false);
  ProgressLine progress(what);
  const size_t total = plan.warmup.size() + plan.measured.size();
  size_t done = 0;
  for (int frame : plan.warmup) {
    progress.show(done++, total);
    renderer.render(frame);
    timer.collect();
  }
  for (int frame : plan.measured) {
    progress.show(done++, total);
    FrameStats stats;
    const auto start = std::chrono::steady_clock::now();
    renderer.render(frame, &stats);
    const auto end = std::chrono::steady_clock::now();
    std::array<double, kStageCount> ms = timer.collect();
    double sum = 0;
    for (double v : ms) sum += v;
    m.frames.push_back(frame);
    m.stage_ms.push_back(ms);
    m.stages_total_ms.push_back(sum);
    m.wall_ms.push_back(std::chrono::duration<double, std::milli>(end - start).count());
    m.render_ms.push_back(stats.render_ms);
    m.hits.push_back(double(stats.photons.hits));
    m.leaf_threshold.push_back(double(stats.photons.leaf_threshold));
    m.batches = stats.photons.batches;
  }
  renderer.set_stage_timer(nullptr);
  return m;
}

struct Histogram {
  std::array<uint64_t, kRadiusBins + 1> bins{};  // the last: > 1.00
  uint64_t valid = 0, degenerate = 0;             // degenerate: valid hit with zero footprint area
  double max_radius = 0;
};

// Footprint radii sqrt(area / pi) of the hits the photon pass buffers hold now (its last batch).
Histogram radius_histogram(Device& device, const Renderer& renderer) {
  const DeviceBuffer* lo = renderer.buffer(BufferSlot::footprint_lo);
  const DeviceBuffer* center = renderer.buffer(BufferSlot::footprint_center);
  if (!lo || !center || !*lo || !*center) throw DeviceError("--radius-histogram: the photon pass has no footprint buffers");
  const size_t slots = std::min(lo->bytes(), center->bytes()) / sizeof(float4);
  std::vector<float4> areas(slots), flags(slots);
  device.download(*lo, areas.data(), slots * sizeof(float4));
  device.download(*center, flags.data(), slots * sizeof(float4));
  Histogram h;
  for (size_t i = 0; i < slots; ++i) {
    uint32_t bits;
    std::memcpy(&bits, &flags[i].w, sizeof(bits));
    if ((bits & PM_HIT_VALID) == 0) continue;
    ++h.valid;
    const double area = areas[i].w;
    if (!(area > 0)) {
      ++h.degenerate;
      continue;
    }
    const double r = std::sqrt(area / M_PI);
    h.max_radius = std::max(h.max_radius, r);
    const int bin = r > kRadiusBins * kRadiusBinWidth ? kRadiusBins : std::min(kRadiusBins - 1, int(r / kRadiusBinWidth));
    ++h.bins[size_t(bin)];
  }
  return h;
}

std::string bin_label(int i) {
  char buf[32];
  if (i == kRadiusBins) std::snprintf(buf, sizeof(buf), "> %.2f", kRadiusBins * kRadiusBinWidth);
  else std::snprintf(buf, sizeof(buf), "%.2f - %.2f", i * kRadiusBinWidth, (i + 1) * kRadiusBinWidth);
  return buf;
}

struct StageThroughput {
  double per_frame = 0;  // units counted per frame
  const char* unit = "";
  const char* counts = "";
};

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

Json spread_json(const Spread& s) { return Json{{"median", s.median}, {"min", s.min}, {"max", s.max}}; }

// A destroyed Renderer leaves its buffers' handles in the device's slot table (the sort's
// alternate buffers, for one), and OpenCL passes every slot to every kernel: clear the table before
// the next Renderer on the same device binds its own buffers.
void unbind_all(Device& device) {
  for (size_t s = 0; s < kBufferSlotCount; ++s) device.unbind(static_cast<BufferSlot>(s));
}

// One measurement with a fresh Renderer that is gone (and unbound) on return.
Measurement measure_with(Device& device, const Scene& scene, const RenderSettings& settings, const FramePlan& plan,
                         const std::string& what) {
  Measurement m;
  {
    Renderer renderer(device, scene, settings);
    StageTimer timer(device);
    m = measure(renderer, timer, plan, what);
  }
  unbind_all(device);
  return m;
}

struct LeafPoint {
  int leaf = 0;  // 0: auto
  Measurement m;
};

int run_bench(const BenchOptions& o) {
  // Everything the user can get wrong is checked before the device is opened.
  const FramePlan plan = plan_frames(o);
  if (!o.json.empty()) check_json_path(o.json);
  std::vector<int> sweep;
  if (!o.leaf_sweep.empty()) sweep = parse_leaf_sweep(o.leaf_sweep);
  RenderSettings settings = render_settings(o.render);
  if (o.radius_histogram && settings.photons.estimator != PM_ESTIMATOR_PD)
    throw InputError(std::string("--radius-histogram: footprint radii exist only for --estimator pd, not ") +
                     estimator_name(settings.photons.estimator));
  if ((o.radius_histogram || !sweep.empty()) && settings.photons.photons == 0)
    throw InputError(std::string(o.radius_histogram ? "--radius-histogram" : "--leaf-sweep") +
                     ": needs photons (--photons is 0)");
  const Scene scene = load_scene(o.render);

  std::unique_ptr<Device> device = create_device(o.render.backend, o.render.device);
  const DeviceInfo info = device->info();
  device->reset_peak();
  auto renderer = std::make_unique<Renderer>(*device, scene, settings);
  StageTimer timer(*device);

  const int width = renderer->width(), height = renderer->height();
  const PhotonPass* pass = renderer->photon_pass();
  RenderSettings effective = settings;  // rmax and radius defaults resolved by the photon pass
  if (pass) effective.photons = pass->settings();
  const uint64_t photons = effective.photons.photons;
  const uint32_t per_batch = pass ? pass->photons_per_batch() : 0;

  std::printf("pmrender bench: %s (%s), %d triangles, %zu light(s)\n", scene.name.c_str(), scene.source.c_str(),
              int(scene.triangle_count()), scene.lights.size());
  std::printf("device: %s --device %d: %s [%s; driver %s]\n", info.backend.c_str(), info.index, info.name.c_str(),
              info.platform.c_str(), info.driver.c_str());
  std::printf("settings: %dx%d %s\n", width, height, effective.describe().c_str());
  std::printf("frames: %zu warmup, %zu measured (%d-%d%s)\n\n", plan.warmup.size(), plan.measured.size(),
              plan.measured.front(), plan.measured.back(), o.frames.empty() ? "" : ", from --frames");
  std::fflush(stdout);

  const Measurement base = measure(*renderer, timer, plan, "bench " + scene.name);

  // k_PD on one extra frame (the last measured one again) with counting on, untimed.
  FrameStats counted;
  if (pass) {
    renderer->set_collect_stats(true);
    renderer->render(base.frames.back(), &counted);
    renderer->set_collect_stats(false);
  }
  const uint64_t peak = device->peak_allocated_bytes();

  // Throughput per stage: what one frame processes.
  const double pixels = double(width) * height;
  const double shading_points = pass ? double(counted.photons.shading_points) : pixels;
  std::array<StageThroughput, kStageCount> through{};
  through[size_t(Stage::camera)] = {pixels * double(1 + scene.lights.size()), "rays/s",
                                    "primary + one shadow ray per light per pixel (mirror rays not counted)"};
  for (Stage s : {Stage::photon_trace, Stage::footprints, Stage::map_morton, Stage::map_sort, Stage::map_tree})
    through[size_t(s)] = {double(photons), "photons/s", "photons emitted per frame"};
  through[size_t(Stage::gather)] = {shading_points, "shading points/s",
                                    "shading points gathered per frame, all batches (counted in the extra frame)"};
  through[size_t(Stage::film)] = {pixels, "pixels/s", "pixels resolved (no read-back in bench)"};

  const Spread total = base.total(), wall = base.wall();
  std::array<Spread, kStageCount> stages;
  double median_sum = 0;
  for (size_t s = 0; s < kStageCount; ++s) {
    stages[s] = base.stage(s);
    median_sum += stages[s].median;
  }

  std::printf("%-22s %10s %10s %10s %7s   %s\n", "stage", "median ms", "min ms", "max ms", "share", "throughput");
  for (size_t s = 0; s < kStageCount; ++s) {
    const double share = median_sum > 0 ? 100.0 * stages[s].median / median_sum : 0.0;
    std::string tp = "-";
    if (stages[s].median > 0 && through[s].per_frame > 0)
      tp = si(through[s].per_frame / (stages[s].median / 1000.0)) + through[s].unit;
    std::printf("%-22s %10.3f %10.3f %10.3f %6.1f%%   %s\n", stage_name(Stage(s)), stages[s].median, stages[s].min,
                stages[s].max, share, tp.c_str());
  }
  std::printf("%-22s %10.3f %10.3f %10.3f\n", "frame (sum of stages)", total.median, total.min, total.max);
  std::printf("%-22s %10.3f %10.3f %10.3f\n", "frame (host wall)", wall.median, wall.min, wall.max);
  std::printf("frames per second: %.2f (host wall), %.2f (sum of stages)\n", base.fps(),
              total.median > 0 ? 1000.0 / total.median : 0.0);
  std::printf("throughput counts: camera = %s", through[size_t(Stage::camera)].counts);
  if (pass) std::printf("; photon stages = photons emitted; gather = %.0f shading points per frame", shading_points);
  std::printf("\n");
  const Spread hits = spread(base.hits);
  const Spread leaf = spread(base.leaf_threshold);
  double k_pd = 0;
  if (pass) {
    std::printf("photons emitted: %llu per frame (%d batch(es) of %u); hits stored: %.0f median (%.0f-%.0f)\n",
                (unsigned long long)photons, base.batches, per_batch, hits.median, hits.min, hits.max);
    k_pd = counted.photons.shading_points ? double(counted.photons.gathered) / double(counted.photons.shading_points) : 0;
    std::printf("photons per gather (k_PD): %.1f (%llu accepted at %llu shading points, frame %d counted again)\n", k_pd,
                (unsigned long long)counted.photons.gathered, (unsigned long long)counted.photons.shading_points,
                base.frames.back());
    std::printf("leaf threshold T: %s, %.0f median\n", effective.photons.leaf_threshold > 0 ? "fixed" : "auto",
                leaf.median);
    std::printf("smoothing s: %s, %.4g in the last batch of frame %d\n", effective.photons.smoothing > 0 ? "fixed" : "auto",
                counted.photons.smoothing, base.frames.back());
  } else {
    std::printf("photons emitted: 0 (direct light only)\n");
  }
  std::printf("peak device memory: %.1f MiB", double(peak) / (1024.0 * 1024.0));
  if (per_batch) std::printf(", %.0f bytes per photon (%u photons per batch)", double(peak) / per_batch, per_batch);
  std::printf("\n");

  Histogram histogram;
  if (o.radius_histogram) {
    histogram = radius_histogram(*device, *renderer);
    std::printf("\nfootprint radii sqrt(area/pi), metres, frame %d%s (after the --rmax clamp, rmax = %g m):\n",
                base.frames.back(), base.batches > 1 ? ", last batch only" : "", double(effective.photons.rmax));
    std::printf("%-14s %12s %8s\n", "radius", "footprints", "share");
    const uint64_t sized = histogram.valid - histogram.degenerate;
    for (int i = 0; i <= kRadiusBins; ++i)
      std::printf("%-14s %12llu %7.2f%%\n", bin_label(i).c_str(), (unsigned long long)histogram.bins[size_t(i)],
                  sized ? 100.0 * double(histogram.bins[size_t(i)]) / double(sized) : 0.0);
    std::printf("valid hits %llu, of which %llu with zero area (not binned); largest radius %.4f m\n",
                (unsigned long long)histogram.valid, (unsigned long long)histogram.degenerate, histogram.max_radius);
  }
  std::fflush(stdout);

  // Leaf sweep: one fresh Renderer per fixed T and one for auto, all measured alike (the first
  // Renderer of a process can see different host times, so the main run is not reused). T only
  // changes device work (map: tree, gather), so the best T is chosen by the device-time FPS.
  std::vector<LeafPoint> points;
  const LeafPoint* best = nullptr;
  if (!sweep.empty()) {
    renderer.reset();
    unbind_all(*device);
    sweep.push_back(0);
    for (int t : sweep) {
      RenderSettings s = settings;
      s.photons.leaf_threshold = t;
      points.push_back({t, measure_with(*device, scene, s, plan,
                                        "leaf sweep T=" + (t > 0 ? std::to_string(t) : std::string("auto")))});
    }
    std::printf("\nleaf sweep (paper Table 1), %zu measured frames each; fps = 1000 / median ms:\n",
                plan.measured.size());
    std::printf("%-12s %14s %16s %12s %12s %10s\n", "T", "frame ms wall", "frame ms stages", "gather ms",
                "fps stages", "fps wall");
    for (const LeafPoint& p : points) {
      std::string label = p.leaf > 0 ? std::to_string(p.leaf)
                                     : "auto (" + std::to_string(int(spread(p.m.leaf_threshold).median)) + ")";
      std::printf("%-12s %14.3f %16.3f %12.3f %12.2f %10.2f\n", label.c_str(), p.m.wall().median, p.m.total().median,
                  p.m.stage(size_t(Stage::gather)).median, p.m.fps_stages(), p.m.fps());
      if (p.leaf > 0 && (!best || p.m.fps_stages() > best->m.fps_stages())) best = &p;
    }
    const LeafPoint& automatic = points.back();
    std::printf("best fixed T: %d (%.2f fps by stages); FPS_auto / FPS_best = %.1f%% by stages, %.1f%% by wall\n",
                best->leaf, best->m.fps_stages(), 100.0 * ratio(automatic.m.fps_stages(), best->m.fps_stages()),
                100.0 * ratio(automatic.m.fps(), best->m.fps()));
  }

  if (!o.json.empty()) {
    Json j;
    j["pmrender_version"] = PMRENDER_VERSION;
    j["date"] = utc_now();
    j["scene"] = {{"name", scene.name},
                  {"source", scene.source},
                  {"triangles", scene.triangle_count()},
                  {"lights", scene.lights.size()}};
    const PhotonSettings& ph = effective.photons;
    j["settings"] = {{"describe", effective.describe()},
                     {"width", width},
                     {"height", height},
                     {"mirror_depth", effective.mirror_depth},
                     {"seed", effective.seed},
                     {"photons", ph.photons},
                     {"batch", ph.batch},
                     {"photons_per_batch", per_batch},
                     {"bounces", ph.bounces},
                     {"estimator", estimator_name(ph.estimator)},
                     {"kernel", ph.kernel_shape == PM_KERNEL_EPANECHNIKOV ? "epanechnikov" : "constant"},
                     {"smoothing", ph.smoothing > 0 ? Json(ph.smoothing) : Json("auto")},
                     {"rmax_m", ph.rmax},
                     {"radius_m", ph.radius},
                     {"knn_k", ph.knn_k},
                     {"leaf_threshold", ph.leaf_threshold > 0 ? Json(ph.leaf_threshold) : Json("auto")},
                     {"leaf_c", ph.leaf_c}};
    j["device"] = {{"backend", info.backend},   {"index", info.index},
                   {"name", info.name},         {"platform", info.platform},
                   {"driver", info.driver},     {"memory_bytes", info.memory_bytes},
                   {"compute_units", info.compute_units}};
    j["frames"] = {{"warmup", plan.warmup}, {"measured", plan.measured}};
    Json stage_list = Json::array();
    for (size_t s = 0; s < kStageCount; ++s) {
      Json row = {{"stage", stage_name(Stage(s))},
                  {"median_ms", stages[s].median},
                  {"min_ms", stages[s].min},
                  {"max_ms", stages[s].max},
                  {"share", median_sum > 0 ? stages[s].median / median_sum : 0.0}};
      if (stages[s].median > 0 && through[s].per_frame > 0)
        row["throughput"] = {{"per_second", through[s].per_frame / (stages[s].median / 1000.0)},
                             {"unit", through[s].unit},
                             {"per_frame", through[s].per_frame},
                             {"counts", through[s].counts}};
      stage_list.push_back(row);
    }
    j["stages"] = stage_list;
    j["frame_ms"] = {{"sum_of_stages", spread_json(total)}, {"host_wall", spread_json(wall)}};
    j["fps"] = {{"host_wall", base.fps()}, {"sum_of_stages", total.median > 0 ? 1000.0 / total.median : 0.0}};
    j["photons"] = {{"emitted_per_frame", photons},
                    {"batches", base.batches},
                    {"per_batch", per_batch},
                    {"hits", spread_json(hits)},
                    {"leaf_threshold", spread_json(leaf)}};
    if (pass)
      j["gather"] = {{"k_pd", k_pd},
                     {"gathered", counted.photons.gathered},
                     {"shading_points", counted.photons.shading_points},
                     {"frame", base.frames.back()}};
    j["memory"] = {{"peak_bytes", peak},
                   {"bytes_per_photon", per_batch ? Json(double(peak) / per_batch) : Json(nullptr)}};
    Json per_frame = Json::array();
    for (size_t i = 0; i < base.frames.size(); ++i) {
      Json stage_ms = Json::object();
      for (size_t s = 0; s < kStageCount; ++s) stage_ms[stage_name(Stage(s))] = base.stage_ms[i][s];
      per_frame.push_back({{"frame", base.frames[i]},
                           {"host_wall_ms", base.wall_ms[i]},
                           {"render_ms", base.render_ms[i]},
                           {"sum_of_stages_ms", base.stages_total_ms[i]},
                           {"hits", base.hits[i]},
                           {"leaf_threshold", base.leaf_threshold[i]},
                           {"stages_ms", stage_ms}});
    }
    j["per_frame"] = per_frame;
    if (o.radius_histogram) {
      Json bins = Json::array();
      for (int i = 0; i <= kRadiusBins; ++i) {
        Json b = {{"label", bin_label(i)}, {"lo", i * kRadiusBinWidth}};
        b["hi"] = i < kRadiusBins ? Json((i + 1) * kRadiusBinWidth) : Json(nullptr);
        b["count"] = histogram.bins[size_t(i)];
        bins.push_back(b);
      }
      j["radius_histogram"] = {{"frame", base.frames.back()},
                               {"last_batch_only", base.batches > 1},
                               {"units", "metres"},
                               {"valid_hits", histogram.valid},
                               {"zero_area", histogram.degenerate},
                               {"max_radius", histogram.max_radius},
                               {"bins", bins}};
    }
    if (!points.empty()) {
      Json rows = Json::array();
      for (const LeafPoint& p : points)
        rows.push_back({{"leaf", p.leaf > 0 ? Json(p.leaf) : Json("auto")},
                        {"t_used_median", spread(p.m.leaf_threshold).median},
                        {"host_wall_ms", spread_json(p.m.wall())},
                        {"sum_of_stages_ms", spread_json(p.m.total())},
                        {"gather_ms", spread_json(p.m.stage(size_t(Stage::gather)))},
                        {"fps_stages", p.m.fps_stages()},
                        {"fps_wall", p.m.fps()}});
      const Measurement& automatic = points.back().m;
      j["leaf_sweep"] = {
          {"points", rows},
          {"best_fixed", best->leaf},
          {"fps_auto_over_best", ratio(automatic.fps_stages(), best->m.fps_stages())},
          {"fps_auto_over_best_wall", ratio(automatic.fps(), best->m.fps())}};
    }
    write_atomically(o.json, j.dump(2) + "\n");
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
