// Leaf sweep (paper Table 1) and footprint radius histogram (paper Table 3) for `pmrender bench`.
#include "cli/bench_photon.h"

#include <cstdio>
#include <memory>
#include <set>
#include <sstream>

#include "render/errors.h"
#include "render/photon/footprint_histogram.h"
#include "render/photon/photon_mapping.h"

namespace pm::cli {

namespace {

using Json = nlohmann::ordered_json;

double ratio(double a, double b) { return b > 0 ? a / b : 0.0; }

Json spread_json(const Spread& s) { return Json{{"median", s.median}, {"min", s.min}, {"max", s.max}}; }

const PhotonSettings* photon_settings(const RenderSettings& settings) {
  return dynamic_cast<const PhotonSettings*>(settings.method.get());
}

}  // namespace

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
  if (text.back() == ',') throw InputError("--leaf-sweep: empty item after the last comma");
  return values;
}

void check_photon_extras(const RenderSettings& settings, bool leaf_sweep, bool radius_histogram) {
  if (!leaf_sweep && !radius_histogram) return;
  const char* option = radius_histogram ? "--radius-histogram" : "--leaf-sweep";
  const PhotonSettings* photon = photon_settings(settings);
  if (!photon) throw InputError(std::string(option) + ": needs --method photon");
  if (photon->photons == 0) throw InputError(std::string(option) + ": needs photons (--photons is 0)");
  if (radius_histogram && photon->estimator != PM_ESTIMATOR_PD)
    throw InputError(std::string("--radius-histogram: footprint radii exist only for --estimator pd, not ") +
                     name_of(kEstimatorNames, photon->estimator));
}

Json print_radius_histogram(Device& device, const Renderer& renderer, int frame) {
  const auto* method = dynamic_cast<const PhotonMapping*>(renderer.method());
  if (!method) throw InputError("--radius-histogram: needs --method photon");
  const FootprintHistogram h = footprint_radius_histogram(device, renderer.buffers(), method->last_hit_count());
  const double rmax = method->settings().rmax;
  std::printf("\nfootprint radii sqrt(area/pi), metres, frame %d, last pass (after the --rmax clamp, rmax = %g m):\n",
              frame, rmax);
  std::printf("%-14s %12s %8s\n", "radius", "footprints", "share");
  const uint64_t sized = h.valid - h.degenerate;
  Json bins = Json::array();
  for (int i = 0; i <= FootprintHistogram::kBins; ++i) {
    const uint64_t count = h.bins[size_t(i)];
    std::printf("%-14s %12llu %7.2f%%\n", FootprintHistogram::bin_label(i).c_str(), (unsigned long long)count,
                sized ? 100.0 * double(count) / double(sized) : 0.0);
    Json b = {{"label", FootprintHistogram::bin_label(i)}, {"lo", i * FootprintHistogram::kBinWidth}};
    b["hi"] = i < FootprintHistogram::kBins ? Json((i + 1) * FootprintHistogram::kBinWidth) : Json(nullptr);
    b["count"] = count;
    bins.push_back(b);
  }
  std::printf("valid hits %llu, of which %llu with zero area (not binned); largest radius %.4f m\n",
              (unsigned long long)h.valid, (unsigned long long)h.degenerate, h.max_radius);
  return Json{{"frame", frame},      {"last_pass_only", true},       {"units", "metres"},
              {"valid_hits", h.valid}, {"zero_area", h.degenerate}, {"max_radius", h.max_radius},
              {"rmax", rmax},        {"bins", bins}};
}

Json run_leaf_sweep(Device& device, const Scene& scene, const RenderSettings& settings, const FramePlan& plan,
                    std::vector<int> thresholds) {
  // One fresh Renderer per fixed T and one for auto, all measured alike (the first Renderer of a
  // process can see different host times, so the main run is not reused). T only changes device
  // work (map: tree, gather), so the best T is chosen by the device-time FPS.
  struct Point {
    int leaf;  // 0: auto
    Measurement m;
  };
  std::vector<Point> points;
  thresholds.push_back(0);
  for (int t : thresholds) {
    auto photon = std::make_shared<PhotonSettings>(*photon_settings(settings));
    photon->leaf_threshold = t;
    RenderSettings s = settings;
    s.method = photon;
    points.push_back({t, measure_with(device, scene, s, plan,
                                      "leaf sweep T=" + (t > 0 ? std::to_string(t) : std::string("auto")))});
  }
  std::printf("\nleaf sweep (paper Table 1), %zu measured frames each; fps = 1000 / median ms:\n", plan.measured.size());
  std::printf("%-12s %14s %16s %12s %12s %10s\n", "T", "frame ms wall", "frame ms stages", "gather ms", "fps stages",
              "fps wall");
  const Point* best = nullptr;
  Json rows = Json::array();
  for (const Point& p : points) {
    const std::string label =
        p.leaf > 0 ? std::to_string(p.leaf) : "auto (" + std::to_string(int(p.m.stat("leaf_threshold").median)) + ")";
    std::printf("%-12s %14.3f %16.3f %12.3f %12.2f %10.2f\n", label.c_str(), p.m.wall().median, p.m.total().median,
                p.m.stage("gather").median, p.m.fps_stages(), p.m.fps());
    if (p.leaf > 0 && (!best || p.m.fps_stages() > best->m.fps_stages())) best = &p;
    rows.push_back({{"leaf", p.leaf > 0 ? Json(p.leaf) : Json("auto")},
                    {"t_used_median", p.m.stat("leaf_threshold").median},
                    {"host_wall_ms", spread_json(p.m.wall())},
                    {"sum_of_stages_ms", spread_json(p.m.total())},
                    {"gather_ms", spread_json(p.m.stage("gather"))},
                    {"fps_stages", p.m.fps_stages()},
                    {"fps_wall", p.m.fps()}});
  }
  const Measurement& automatic = points.back().m;
  std::printf("best fixed T: %d (%.2f fps by stages); FPS_auto / FPS_best = %.1f%% by stages, %.1f%% by wall\n",
              best->leaf, best->m.fps_stages(), 100.0 * ratio(automatic.fps_stages(), best->m.fps_stages()),
              100.0 * ratio(automatic.fps(), best->m.fps()));
  return Json{{"points", rows},
              {"best_fixed", best->leaf},
              {"fps_auto_over_best", ratio(automatic.fps_stages(), best->m.fps_stages())},
              {"fps_auto_over_best_wall", ratio(automatic.fps(), best->m.fps())}};
}

}  // namespace pm::cli
