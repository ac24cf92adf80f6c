// Parsing and expansion of the tradeoff grid (tradeoff_grid.h).
#include "cli/tradeoff_grid.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "render/errors.h"
#include "render/path/path_settings.h"
#include "render/photon/photon_settings.h"
#include "render/radiosity/radiosity_settings.h"

namespace pm::cli {

namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> items;
  std::string item;
  std::istringstream in(text);
  while (std::getline(in, item, ',')) items.push_back(item);
  if (!text.empty() && text.back() == ',') items.push_back("");
  return items;
}

std::string number_text(double v) {
  char text[32];
  std::snprintf(text, sizeof(text), "%g", v);
  return text;
}

// Whole numbers only where the setting counts something.
std::vector<uint64_t> whole_numbers(const std::string& text, const std::string& option, uint64_t most) {
  std::vector<uint64_t> out;
  for (double v : parse_number_list(text, option)) {
    if (v != std::floor(v) || v > double(most))
      throw InputError(option + ": expected whole numbers from 1 to " + std::to_string(most) + ", got " + number_text(v));
    out.push_back(uint64_t(v));
  }
  return out;
}

}  // namespace

std::vector<double> parse_number_list(const std::string& text, const std::string& option, bool zero_allowed) {
  std::vector<double> values;
  for (const std::string& item : split(text)) {
    char* end = nullptr;
    const double v = std::strtod(item.c_str(), &end);
    if (item.empty() || !end || *end != '\0' || !std::isfinite(v) || v < 0 || (v == 0 && !zero_allowed))
      throw InputError(option + ": expected a comma-separated list of " + (zero_allowed ? "numbers >= 0" : "positive numbers") +
                       ", got '" + text + "'");
    values.push_back(v);
  }
  if (values.empty()) throw InputError(option + ": empty list");
  return values;
}

std::string TradeoffSetting::label() const {
  std::string text = estimator;
  if (estimator == "radiosity")
    return text + (parameter > 0 ? " edge=" + number_text(parameter) : " edge=auto") + " nC=" + std::to_string(directions);
  if (estimator == "radiosity-fg")
    return text + (parameter > 0 ? " edge=" + number_text(parameter) : " edge=auto") + " nC=" + std::to_string(directions) +
           " rays=" + std::to_string(rays) + " x" + std::to_string(passes);
  if (estimator == "path") text += " spp=" + number_text(parameter);
  else text += " " + std::to_string(photons);
  if (estimator == "pd") text += " s=" + number_text(parameter);
  if (estimator == "knn") text += " k=" + number_text(parameter);
  if (estimator == "radius") text += parameter > 0 ? " r=" + number_text(parameter) : " r=auto";
  if (estimator == "fg") text += " rays=" + number_text(parameter);
  text += " x" + std::to_string(passes);
  return progressive == "shrink" ? text + " shrink" : text;
}

std::string TradeoffSetting::series() const {
  if (estimator == "path") return "path tracer";
  if (estimator == "radiosity") return "radiosity";
  if (estimator == "radiosity-fg") return "radiosity final gather";
  return "photon " + estimator + (progressive == "shrink" ? " shrink" : "");
}

RenderSettings TradeoffSetting::render_settings(const RenderSettings& base, int bounces, float rmax) const {
  RenderSettings s = base;
  s.passes = passes;
  if (estimator == "path") {
    auto path = std::make_shared<PathSettings>();
    path->samples = uint32_t(parameter);
    path->bounces = bounces;
    s.method = path;
  } else if (estimator == "radiosity" || estimator == "radiosity-fg") {
    auto radiosity = std::make_shared<RadiositySettings>();
    radiosity->max_edge = float(parameter);
    radiosity->directions = directions;
    radiosity->bounces = bounces;
    if (estimator == "radiosity-fg") radiosity->final_gather = rays;
    s.method = radiosity;
  } else {
    auto photon = std::make_shared<PhotonSettings>();
    photon->photons = photons;
    photon->bounces = bounces;
    photon->rmax = rmax;
    value_of(kEstimatorNames, estimator == "fg" ? "pd" : estimator, &photon->estimator);
    if (estimator == "pd") photon->smoothing = float(parameter);
    if (estimator == "knn") photon->knn_k = int(parameter);
    if (estimator == "radius") photon->radius = float(parameter);
    // Final gathering over the pd map at its automatic smoothing (the method's default).
    if (estimator == "fg") photon->final_gather = uint32_t(parameter);
    value_of(kProgressiveNames, progressive, &photon->progressive);
    photon->alpha = alpha;
    s.method = photon;
  }
  s.validate();
  return s;
}

namespace {

// The settings a photon estimator's shrinking passes start from, as the renderer resolves them:
// their alpha (the one given, or the estimator's default where 0) and whether one shrink pass
// differs from one averaged pass (pd's shrinking passes have defaults of their own).
PhotonSettings shrinking(const std::string& estimator, float alpha) {
  PhotonSettings probe;
  value_of(kEstimatorNames, estimator == "fg" ? "pd" : estimator, &probe.estimator);
  probe.final_gather = estimator == "fg" ? 1 : 0;
  probe.progressive = kProgressiveShrink;
  probe.alpha = alpha;
  return probe;
}

}  // namespace

std::vector<TradeoffSetting> expand_tradeoff_grid(const TradeoffGridLists& lists) {
  const std::vector<uint64_t> photons = whole_numbers(lists.photons, "--photons", uint64_t(1) << 28);
  const std::vector<uint64_t> passes = whole_numbers(lists.passes, "--passes", 1u << 20);
  const std::vector<uint64_t> spp = whole_numbers(lists.spp, "--spp", 65536);
  const std::vector<uint64_t> k = whole_numbers(lists.k, "--k", 256);
  const std::vector<double> smoothing = parse_number_list(lists.smoothing, "--smoothing");
  const std::vector<double> radius = parse_number_list(lists.radius, "--radius", true);
  const std::vector<double> max_edge = parse_number_list(lists.max_edge, "--max-edge", true);
  const std::vector<uint64_t> directions = whole_numbers(lists.directions, "--directions", 65536);
  const std::vector<uint64_t> rays = whole_numbers(lists.final_gather, "--final-gather", 65536);
  const std::vector<std::string> modes = split(lists.progressive);
  for (const std::string& mode : modes) {
    int unused = 0;
    if (!value_of(kProgressiveNames, mode, &unused))
      throw InputError("--progressive: expected " + names_list(kProgressiveNames) + ", got '" + mode + "'");
  }
  if (!(lists.alpha >= 0 && lists.alpha < 1))
    throw InputError("--alpha: expected a number between 0 and 1 (exclusive), or 0 for the defaults, got " +
                     number_text(lists.alpha));
  std::vector<TradeoffSetting> grid;
  for (const std::string& estimator : split(lists.estimators)) {
    if (estimator == "radiosity") {
      for (double edge : max_edge)
        for (uint64_t n : directions) grid.push_back(TradeoffSetting{estimator, 0, 1, edge, "average", lists.alpha, uint32_t(n)});
      continue;
    }
    if (estimator == "radiosity-fg") {
      for (double edge : max_edge)
        for (uint64_t n : directions)
          for (uint64_t r : rays)
            for (uint64_t p : passes)
              grid.push_back(TradeoffSetting{estimator, 0, uint32_t(p), edge, "average", lists.alpha, uint32_t(n), uint32_t(r)});
      continue;
    }
    std::vector<double> parameters;
    if (estimator == "path") for (uint64_t v : spp) parameters.push_back(double(v));
    else if (estimator == "pd") parameters = smoothing;
    else if (estimator == "knn") for (uint64_t v : k) parameters.push_back(double(v));
    else if (estimator == "radius") parameters = radius;
    else if (estimator == "fg") for (uint64_t v : rays) parameters.push_back(double(v));
    else throw InputError("--estimators: expected pd, knn, radius, fg, path, radiosity or radiosity-fg, got '" + estimator + "'");
    const bool photon_mapping = estimator != "path";
    const std::vector<uint64_t> counts = photon_mapping ? photons : std::vector<uint64_t>{0};
    for (uint64_t count : counts)
      for (double parameter : parameters)
        for (uint64_t p : passes)
          for (const std::string& mode : photon_mapping ? modes : std::vector<std::string>{"average"}) {
            // Shrinking starts at the first pass's footprints: one shrink pass is the average pass,
            // unless the shrinking passes have defaults of their own (pd's weigh photons on tilted
            // facets; PhotonSettings::shrinking_pd).
            const PhotonSettings shrink = shrinking(estimator, lists.alpha);
            if (mode == "shrink" && p == 1 && modes.size() > 1 && !shrink.shrinking_pd()) continue;
            grid.push_back(TradeoffSetting{estimator, count, uint32_t(p), parameter, mode,
                                           mode == "shrink" ? shrink.alpha_or_default() : lists.alpha});
          }
  }
  return grid;
}

}  // namespace pm::cli
