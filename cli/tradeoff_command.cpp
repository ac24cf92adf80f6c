// `pmrender tradeoff [SCENE] --reference REF.exr | --reference-spp N`: what each setting costs and
// how wrong it is. Renders the reference with the path tracer if asked (or reads one), sweeps a
// grid of settings (tradeoff_grid.h), times each with the bench machinery (per-stage device
// times, medians over --repeat frames) and measures its error against the reference
// (tradeoff_report.h), then writes a table, a JSON file and an SVG plot of error against time
// with the Pareto front marked. --budget-ms and --target-error print the best setting found for
// them. Everything the user can get wrong is checked before the device is opened.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "cli/bench_measure.h"
#include "cli/commands.h"
#include "cli/number_parsing.h"
#include "cli/progress_line.h"
#include "cli/startup_report.h"
#include "cli/tradeoff_grid.h"
#include "cli/tradeoff_report.h"
#include "render/atomic_file.h"
#include "render/device.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/image_metrics.h"
#include "render/path/path_settings.h"
#include "render/tradeoff/pareto.h"
#include "scene_io/cornell_box.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

namespace {

namespace fs = std::filesystem;

struct TradeoffOptions {
  std::string scene_path, backend = "auto", resolution, output, reference, metric = "relmae";
  std::string error_levels = "0.05,0.02,0.01,0.005";
  int device = 0, mirror_depth = 1, bounces = 2, warmup = 1, repeat = 3;
  uint32_t seed = 1, reference_spp = 0, reference_passes = 4;
  double budget_ms = 0, target_error = 0;
  float rmax = 0;
  bool quiet = false;
  TradeoffGridLists grid;
};

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

// A --budget-ms or --target-error answer: a line for the report and an entry in the JSON.
void add_pick(const std::vector<TradeoffRow>& rows, int best, const std::string& metric, const char* key, double limit,
              const std::string& what, const char* none, std::string* picks, nlohmann::ordered_json* j) {
  std::string answer = none;
  nlohmann::ordered_json label = nullptr;
  if (best >= 0) {
    const TradeoffRow& r = rows[size_t(best)];
    char text[256];
    std::snprintf(text, sizeof(text), "%s (%.3f ms, %s %.4g)", r.setting.label().c_str(), r.device_ms.median,
                  metric.c_str(), r.error(metric));
    answer = text;
    label = r.setting.label();
  }
  *picks += what + answer + "\n";
  (*j)[key] = {{"limit", limit}, {"best", label}};
}

// The reference: read from --reference, or rendered by the path tracer and written beside the
// results so the next sweep can reuse it. A rendered reference also measures its own noise: its
// two halves of passes differ by twice the error one would expect of the whole (relMAE), which
// goes to *noise; unknown (0) for a reference read from file.
FrameImage make_reference(const TradeoffOptions& o, Device& device, const Scene& scene, const RenderSettings& base,
                          const fs::path& folder, double* noise) {
  *noise = 0;
  if (!o.reference.empty()) return read_exr(o.reference);
  RenderSettings settings = base;
  auto path = std::make_shared<PathSettings>();
  path->samples = o.reference_spp;
  path->bounces = o.bounces;
  settings.method = path;
  settings.passes = o.reference_passes;
  settings.seed = base.seed + 1000003u;  // no grid render shares its random numbers
  Renderer renderer(device, scene, settings);
  if (!o.quiet)
    std::printf("reference: path tracer, %u passes of %u paths per pixel ...\n", o.reference_passes, o.reference_spp);
  std::fflush(stdout);
  const auto start = std::chrono::steady_clock::now();
  renderer.begin_frame(0);
  const uint32_t half = o.reference_passes / 2;
  for (uint32_t i = 0; i < half; ++i) renderer.run_pass();
  FrameImage first_half;
  if (half > 0) {
    renderer.wait();
    first_half = renderer.read_image();
  }
  for (uint32_t i = half; i < o.reference_passes; ++i) renderer.run_pass();
  renderer.wait();
  FrameImage image = renderer.read_image();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (half > 0 && 2 * half == o.reference_passes) {
    // whole = (first + second) / 2, so second = 2 whole - first.
    std::vector<float> second = image.find("")->rgb;
    const std::vector<float>& first = first_half.find("")->rgb;
    for (size_t i = 0; i < second.size(); ++i) second[i] = 2.0f * second[i] - first[i];
    const ImageComparison c = compare_images(second, first, image.width, image.height);
    *noise = c.relmae / 2.0;
  }
  image.attributes = {{"pmrender/version", PMRENDER_VERSION}, {"pmrender/settings", renderer.describe()},
                      {"pmrender/render_ms", std::to_string(seconds * 1000.0)}};
  const std::string file = (folder / "reference.exr").string();
  write_exr(file, image, true);
  if (!o.quiet)
    std::printf("wrote %s (%s%s)\n", file.c_str(), seconds_text(seconds).c_str(),
                *noise > 0 ? (", own noise about " + std::to_string(100 * *noise).substr(0, 5) + " % relMAE").c_str() : "");
  std::fflush(stdout);  // seen at once in a log file too, before the grid's long silence
  return image;
}

int run_tradeoff(const TradeoffOptions& o) {
  if (o.reference.empty() == (o.reference_spp == 0))
    throw InputError("--reference or --reference-spp: give exactly one of them");
  if (!is_tradeoff_metric(o.metric)) throw InputError("--metric: expected relmae, relmse or flip, got '" + o.metric + "'");
  if (o.warmup < 0) throw InputError("--warmup: expected 0 or more frames");
  if (o.repeat < 1) throw InputError("--repeat: expected at least 1 measured frame");
  if (o.budget_ms < 0 || !std::isfinite(o.budget_ms)) throw InputError("--budget-ms: expected a positive time");
  if (o.target_error < 0 || !std::isfinite(o.target_error)) throw InputError("--target-error: expected a positive error");
  if (o.reference_passes < 1) throw InputError("--reference-passes: expected at least 1");
  const std::vector<TradeoffSetting> grid = expand_tradeoff_grid(o.grid);
  const std::vector<double> levels = parse_number_list(o.error_levels, "--error-levels");
  const Scene scene = o.scene_path.empty() ? builtin_cornell_box() : load_scene_file(o.scene_path);
  RenderSettings base;
  base.mirror_depth = o.mirror_depth;
  base.seed = o.seed;
  if (!o.resolution.empty()) parse_resolution(o.resolution, &base.width, &base.height);
  std::vector<RenderSettings> settings;
  for (const TradeoffSetting& s : grid) settings.push_back(s.render_settings(base, o.bounces, o.rmax));
  if (o.reference_spp > 0) {
    PathSettings reference;
    reference.samples = o.reference_spp;
    try {
      reference.validate();
    } catch (const SettingError&) {
      throw InputError("--reference-spp: expected 1 to 65536 paths per pixel and pass");
    }
  }
  const int width = base.width > 0 ? base.width : scene.camera.width;
  const int height = base.height > 0 ? base.height : scene.camera.height;
  if (!o.reference.empty()) {
    const FrameImage header = read_exr(o.reference);
    if (header.width != width || header.height != height)
      throw InputError(o.reference + ": image is " + std::to_string(header.width) + "x" + std::to_string(header.height) +
                       " but the renders are " + std::to_string(width) + "x" + std::to_string(height) +
                       " (--resolution)");
    require_finite(require_layer(header, "combined", o.reference).rgb, header.width, o.reference, "combined");
  }
  const fs::path folder = o.output.empty() ? fs::path("out") / ("tradeoff-" + scene.name) : fs::path(o.output);
  std::error_code ec;
  if (fs::exists(folder, ec) && !fs::is_directory(folder, ec))
    throw InputError("-o: '" + folder.string() + "' exists and is not a folder");

  std::unique_ptr<Device> device = create_device(o.backend, o.device);
  print_device_startup_messages({device.get()}, false, o.quiet);
  const DeviceInfo info = device->info();
  if (!o.quiet)
    std::printf("pmrender tradeoff: %s, %dx%d, %zu settings, on %s (%s)\n", scene.name.c_str(), width, height,
                grid.size(), info.name.c_str(), info.backend.c_str());
  fs::create_directories(folder);
  double reference_noise = 0;
  const FrameImage reference = make_reference(o, *device, scene, base, folder, &reference_noise);

  // Warmup frames 1.., measured frames after them: never frame 0 with the reference's seed.
  FramePlan plan;
  for (int f = 1; f <= o.warmup; ++f) plan.warmup.push_back(f);
  for (int f = o.warmup + 1; f <= o.warmup + o.repeat; ++f) plan.measured.push_back(f);
  std::vector<TradeoffRow> rows;
  const auto start = std::chrono::steady_clock::now();
  for (size_t i = 0; i < grid.size(); ++i) {
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::string what = "[" + std::to_string(i + 1) + "/" + std::to_string(grid.size());
    if (i > 0) what += ", ETA " + seconds_text(elapsed / double(i) * double(grid.size() - i));
    what += "] " + grid[i].label();
    // Every measured frame on a renderer of its own, after the warmup frames on another: a still
    // image's cost from the scene on the device, with nothing kept from an earlier frame (a
    // method may keep work between frames of a still scene: radiosity its links and solution).
    // The error is the last measured frame's: what one frame at this setting looks like.
    if (!plan.warmup.empty()) measure_with(*device, scene, settings[i], FramePlan{plan.warmup, {}}, what);
    Measurement m;
    std::unique_ptr<Renderer> renderer;
    for (int frame : plan.measured) {
      renderer = std::make_unique<Renderer>(*device, scene, settings[i]);
      StageTimer timer(*device);
      const Measurement one = measure(*renderer, timer, FramePlan{{}, {frame}}, what);
      m.stages_total_ms.insert(m.stages_total_ms.end(), one.stages_total_ms.begin(), one.stages_total_ms.end());
      m.wall_ms.insert(m.wall_ms.end(), one.wall_ms.begin(), one.wall_ms.end());
    }
    rows.push_back(TradeoffRow{grid[i], m.total(), m.wall(), tradeoff_errors(reference, renderer->read_image()), false});
  }
  mark_pareto_front(rows, o.metric);

  // The reference's noise is known for relMAE only; twice it is where errors stop meaning much.
  const double floor = o.metric == "relmae" ? 2 * reference_noise : 0.0;
  const std::string table = tradeoff_table(rows, o.metric) + "\n" + time_to_error_table(rows, o.metric, levels, floor);
  nlohmann::ordered_json j;
  j["pmrender_version"] = PMRENDER_VERSION;
  j["scene"] = {{"name", scene.name}, {"source", scene.source}, {"triangles", scene.triangle_count()}};
  j["device"] = {{"backend", info.backend}, {"name", info.name}, {"driver", info.driver}};
  j["resolution"] = {width, height};
  j["bounces"] = o.bounces;
  j["mirror_depth"] = o.mirror_depth;
  j["reference"] = o.reference.empty()
                       ? nlohmann::ordered_json{{"path_tracer_spp", o.reference_spp}, {"passes", o.reference_passes},
                                                {"file", (folder / "reference.exr").string()}}
                       : nlohmann::ordered_json{{"file", o.reference}};
  j["frames"] = {{"warmup", o.warmup}, {"measured", o.repeat}};
  j["reference_noise_relmae"] = reference_noise > 0 ? nlohmann::ordered_json(reference_noise) : nlohmann::ordered_json(nullptr);
  j["metric"] = o.metric;
  j["settings"] = tradeoff_json_rows(rows);
  j["time_to_error"] = time_to_error_json(rows, o.metric, levels, floor);
  j["fastest"] = fastest_per_level_json(rows, o.metric, levels);
  std::vector<TradeoffPoint> points;
  for (const TradeoffRow& r : rows) points.push_back({r.device_ms.median, r.error(o.metric)});
  std::string picks;
  if (o.budget_ms > 0)
    add_pick(rows, best_within_time(points, o.budget_ms), o.metric, "budget_ms", o.budget_ms,
             "best within " + number_text(o.budget_ms) + " ms: ", "none of the settings is that fast", &picks, &j);
  if (o.target_error > 0)
    add_pick(rows, fastest_within_error(points, o.target_error), o.metric, "target_error", o.target_error,
             "fastest with " + o.metric + " <= " + number_text(o.target_error) + ": ",
             "none of the settings is that accurate", &picks, &j);
  const std::string title = scene.name + ", " + std::to_string(width) + "x" + std::to_string(height) + ", " + info.name;
  write_file_atomically((folder / "tradeoff.txt").string(), table + picks);
  write_file_atomically((folder / "tradeoff.json").string(), j.dump(2) + "\n");
  write_file_atomically((folder / "tradeoff.svg").string(), tradeoff_svg(rows, o.metric, title));
  if (!o.quiet) {
    std::printf("\n%s\n%s", table.c_str(), picks.c_str());
    std::printf("wrote %s/tradeoff.txt, tradeoff.json, tradeoff.svg\n", folder.string().c_str());
  } else {
    std::printf("%s", picks.c_str());
  }
  return 0;
}

}  // namespace

Run add_tradeoff_command(CLI::App& app) {
  auto o = std::make_shared<TradeoffOptions>();
  CLI::App* cmd = app.add_subcommand(
      "tradeoff", "Time a grid of settings and measure each one's error against a reference: table, JSON, SVG plot");
  cmd->add_option("scene", o->scene_path, "Scene file; default: the built-in Cornell box");
  cmd->add_option("--reference", o->reference, "Reference image (EXR, combined layer; its direct layer if any)");
  cmd->add_option("--reference-spp", o->reference_spp, "Render the reference with the path tracer: paths per pixel "
                                                       "and pass");
  cmd->add_option("--reference-passes", o->reference_passes, "Passes of the rendered reference")->capture_default_str();
  cmd->add_option("-o,--output", o->output, "Folder for tradeoff.{txt,json,svg} and reference.exr")
      ->default_str("out/tradeoff-<scene>");
  cmd->add_option("--backend", o->backend, "auto, cuda or opencl")->check(CLI::IsMember({"auto", "cuda", "opencl"}));
  cmd->add_option("--device", o->device, "Device index within the backend");
  cmd->add_option("--resolution", o->resolution, "WIDTHxHEIGHT, overrides the scene camera's");
  cmd->add_option("--mirror-depth", o->mirror_depth, "Perfect-mirror bounces followed from the eye")->capture_default_str();
  cmd->add_option("--bounces", o->bounces, "Diffuse bounces of indirect light, every setting and the reference")
      ->capture_default_str();
  cmd->add_option("--seed", o->seed, "Random seed")->capture_default_str();
  cmd->add_option("--rmax", o->rmax, "Largest footprint semiaxis and k-NN search radius of every photon setting, "
                                     "metres (default: 10% of the scene diagonal)");
  const std::string grid = "Grid (comma-separated lists)";
  cmd->add_option("--estimators", o->grid.estimators, "pd, knn, radius (photon mapping), fg (final gathering over "
                                                      "the pd map), path (path tracer), radiosity (vertex link "
                                                      "radiosity) and radiosity-fg (final gathering over its solution)")
      ->capture_default_str()->group(grid);
  cmd->add_option("--photons", o->grid.photons, "Photons per pass")->capture_default_str()->group(grid);
  cmd->add_option("--passes", o->grid.passes, "Passes per frame, every estimator")->capture_default_str()->group(grid);
  cmd->add_option("--smoothing", o->grid.smoothing, "Smoothing s of --estimator pd")->capture_default_str()->group(grid);
  cmd->add_option("--k", o->grid.k, "Neighbours of --estimator knn")->capture_default_str()->group(grid);
  cmd->add_option("--radius", o->grid.radius, "Gather radii of --estimator radius, metres (0: 5 % of the scene diagonal)")
      ->capture_default_str()->group(grid);
  cmd->add_option("--progressive", o->grid.progressive, "How photon passes combine: average, shrink or "
                                                        "average,shrink (shrink only where passes > 1)")
      ->capture_default_str()->group(grid);
  cmd->add_option("--alpha", o->grid.alpha, "Shrink's alpha, 0 < alpha < 1; 0: the renderer's defaults (0.2 for pd, 2/3 for "
                                               "the others; docs/progressive.md)")
      ->transform(finite_float())->capture_default_str()->group(grid);
  cmd->add_option("--spp", o->grid.spp, "Paths per pixel and pass of the path tracer")->capture_default_str()->group(grid);
  cmd->add_option("--final-gather", o->grid.final_gather, "Gather rays per shading point and pass of --estimators fg "
                                                        "and radiosity-fg (final gathering)")
      ->capture_default_str()->group(grid);
  cmd->add_option("--max-edge", o->grid.max_edge, "Radiosity's (and radiosity-fg's) longest element edges, metres (0: the scene diagonal / 50)")
      ->capture_default_str()->group(grid);
  cmd->add_option("--directions", o->grid.directions, "Radiosity's (and radiosity-fg's) link directions per element (nC)")
      ->capture_default_str()->group(grid);
  cmd->add_option("--warmup", o->warmup, "Frames rendered first and not timed, per setting")->capture_default_str();
  cmd->add_option("--repeat", o->repeat, "Timed frames per setting (medians)")->capture_default_str();
  cmd->add_option("--metric", o->metric, "Error for the front and the picks: relmae, relmse or flip")
      ->capture_default_str();
  cmd->add_option("--error-levels", o->error_levels, "Errors (--metric) to report the time to reach, per estimator")
      ->capture_default_str();
  cmd->add_option("--budget-ms", o->budget_ms, "Print the most accurate setting within this device time per frame");
  cmd->add_option("--target-error", o->target_error, "Print the fastest setting with at most this error (--metric)");
  cmd->add_flag("-q,--quiet", o->quiet, "Print only the picks");
  return [o] { return run_tradeoff(*o); };
}

}  // namespace pm::cli
