// Parsing and expansion of the tradeoff grid (tradeoff_grid.h).
#include "cli/tradeoff_grid.h"

#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>

#include "render/errors.h"
#include "render/path/path_settings.h"
#include "render/photon/photon_settings.h"

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
  if (estimator == "path") text += " spp=" + number_text(parameter);
  else text += " " + std::to_string(photons);
  if (estimator == "pd") text += " s=" + number_text(parameter);
  if (estimator == "knn") text += " k=" + number_text(parameter);
  if (estimator == "radius") text += parameter > 0 ? " r=" + number_text(parameter) : " r=auto";
  return text + " x" + std::to_string(passes);
}

std::string TradeoffSetting::series() const { return estimator == "path" ? "path tracer" : "photon " + estimator; }

RenderSettings TradeoffSetting::render_settings(const RenderSettings& base, int bounces, float rmax) const {
  RenderSettings s = base;
  s.passes = passes;
  if (estimator == "path") {
    auto path = std::make_shared<PathSettings>();
    path->samples = uint32_t(parameter);
    path->bounces = bounces;
    s.method = path;
  } else {
    auto photon = std::make_shared<PhotonSettings>();
    photon->photons = photons;
    photon->bounces = bounces;
    photon->rmax = rmax;
    value_of(kEstimatorNames, estimator, &photon->estimator);
    if (estimator == "pd") photon->smoothing = float(parameter);
    if (estimator == "knn") photon->knn_k = int(parameter);
    if (estimator == "radius") photon->radius = float(parameter);
    s.method = photon;
  }
  s.validate();
  return s;
}

std::vector<TradeoffSetting> expand_tradeoff_grid(const TradeoffGridLists& lists) {
  const std::vector<uint64_t> photons = whole_numbers(lists.photons, "--photons", uint64_t(1) << 28);
  const std::vector<uint64_t> passes = whole_numbers(lists.passes, "--passes", 1u << 20);
  const std::vector<uint64_t> spp = whole_numbers(lists.spp, "--spp", 65536);
  const std::vector<uint64_t> k = whole_numbers(lists.k, "--k", 256);
  const std::vector<double> smoothing = parse_number_list(lists.smoothing, "--smoothing");
  const std::vector<double> radius = parse_number_list(lists.radius, "--radius", true);
  std::vector<TradeoffSetting> grid;
  for (const std::string& estimator : split(lists.estimators)) {
    std::vector<double> parameters;
    if (estimator == "path") for (uint64_t v : spp) parameters.push_back(double(v));
    else if (estimator == "pd") parameters = smoothing;
    else if (estimator == "knn") for (uint64_t v : k) parameters.push_back(double(v));
    else if (estimator == "radius") parameters = radius;
    else throw InputError("--estimators: expected pd, knn, radius or path, got '" + estimator + "'");
    const std::vector<uint64_t> counts = estimator == "path" ? std::vector<uint64_t>{0} : photons;
    for (uint64_t count : counts)
      for (double parameter : parameters)
        for (uint64_t p : passes) grid.push_back(TradeoffSetting{estimator, count, uint32_t(p), parameter});
  }
  return grid;
}

}  // namespace pm::cli
