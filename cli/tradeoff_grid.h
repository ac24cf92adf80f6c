// The grid of settings `pmrender tradeoff` sweeps: which estimators, photon counts, smoothing /
// k / radius values, passes, progressive modes, path-tracer samples and radiosity's element sizes
// and link directions, parsed from comma-separated lists, expanded into one RenderSettings per
// point, each with a short label for tables and plots.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "render/renderer.h"

namespace pm::cli {

struct TradeoffSetting {
  // pd, knn, radius, fg (photon mapping; fg: final gathering over pd), path, radiosity or
  // radiosity-fg (final gathering over the radiosity solution)
  std::string estimator;
  uint64_t photons = 0;   // photons per pass (photon mapping)
  uint32_t passes = 1;
  // pd: smoothing s; knn: k; radius: metres (0: the scene default); fg: gather rays; path: spp;
  // radiosity, radiosity-fg: the longest element edge, metres (0: the scene default)
  double parameter = 0;
  std::string progressive = "average";  // how a photon estimator's passes combine: average or shrink
  float alpha = 0.0f;                   // shrink's alpha; 0: the estimator's default (PhotonSettings)
  uint32_t directions = 0;              // radiosity, radiosity-fg: link directions per element (nC)
  uint32_t rays = 0;                    // radiosity-fg: gather rays per shading point and pass

  // "pd 262144 s=8 x4", "pd 262144 s=8 x4 shrink", "path spp=16 x4", "radiosity edge=auto nC=256",
  // "radiosity-fg edge=auto nC=256 rays=16 x4"
  std::string label() const;
  std::string series() const;  // the plot's colour: "photon pd", "photon pd shrink", "path tracer", "radiosity"
  // base (scene, resolution, seed, mirror depth) with this point's method and passes.
  // rmax: footprint clamp and k-NN search radius of the photon estimators, metres (0: default).
  RenderSettings render_settings(const RenderSettings& base, int bounces, float rmax) const;
};

// The lists as given on the command line.
struct TradeoffGridLists {
  std::string estimators = "pd,knn,radius,fg,path,radiosity,radiosity-fg";
  std::string photons = "65536,262144,1048576";
  std::string passes = "1,4";
  std::string smoothing = "8";
  std::string k = "64";
  std::string radius = "0";
  std::string spp = "1,4,16";
  std::string final_gather = "16";  // fg's and radiosity-fg's gather rays per shading point and pass
  std::string max_edge = "0";      // radiosity's (and radiosity-fg's) element sizes, metres (0: the scene default)
  std::string directions = "256";  // radiosity's (and radiosity-fg's) link directions per element
  std::string progressive = "average";  // average, shrink or both; shrink only where passes > 1
  float alpha = 0.0f;  // 0: each estimator's default
};

// Every combination, estimator by estimator in the order given; radiosity, deterministic, gets one
// pass whatever --passes says. InputError naming the option ("--photons: ...") for an empty list,
// a bad number or an unknown estimator.
std::vector<TradeoffSetting> expand_tradeoff_grid(const TradeoffGridLists& lists);

// "1,4,16" -> {1, 4, 16}: finite numbers, each > 0 (>= 0 where zero_allowed); InputError naming
// the option otherwise.
std::vector<double> parse_number_list(const std::string& text, const std::string& option, bool zero_allowed = false);

}  // namespace pm::cli
