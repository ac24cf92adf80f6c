// `pmrender compare REFERENCE TEST`: every image metric of render/image_metrics.h between one
// layer of two EXR files, the chosen metric last with pass or fail against a threshold, and
// optionally a per-pixel error map. Exit codes: 0 at or under the threshold, 1 over it, 2 on bad
// input (unreadable file, different sizes, missing layer, NaN or Inf: the message names the file
// and, for non-finite values, the pixel).
#include <cfloat>
#include <cmath>
#include <cstdio>
#include <memory>
#include <string>

#include "cli/commands.h"
#include "cli/number_parsing.h"
#include "cli/output_checks.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/image_metrics.h"

namespace pm::cli {

namespace {

struct CompareOptions {
  std::string reference, test;
  std::string metric = "flip";
  double threshold = 0;
  CLI::Option* threshold_option = nullptr;  // not given: the metric's default
  std::string diff;
  std::string layer = "combined";
  double ppd = flip::default_pixels_per_degree();
};

// Defaults when --threshold is not given. flip: the golden-image tolerance (golden/README.md);
// the others: 1 % (relative ones) or 0.01 radiance units (rmse).
double default_threshold(ImageMetric metric) {
  switch (metric) {
    case ImageMetric::flip: return 0.05;
    case ImageMetric::rmse: return 0.01;
    case ImageMetric::relmse: return 0.01;
    case ImageMetric::mean: return 0.01;
    case ImageMetric::relmae: return 0.05;
  }
  return 0;
}

std::string describe(ImageMetric metric, const ImageComparison& c) {
  char text[200];
  switch (metric) {
    case ImageMetric::flip:
      std::snprintf(text, sizeof(text), "mean HDR-FLIP at %.1f px/degree, exposures %.2f to %.2f in %d steps", c.ppd,
                    c.exposures.start, c.exposures.stop, c.exposures.count);
      break;
    case ImageMetric::rmse: std::snprintf(text, sizeof(text), "root mean squared difference"); break;
    case ImageMetric::relmse: std::snprintf(text, sizeof(text), "mean of (test - ref)^2 / (ref^2 + 0.01)"); break;
    case ImageMetric::mean: std::snprintf(text, sizeof(text), "relative difference of the image means"); break;
    case ImageMetric::relmae: std::snprintf(text, sizeof(text), "sum |test - ref| / sum ref"); break;
  }
  return text;
}

int run_compare(const CompareOptions& o) {
  const ImageMetric chosen = parse_image_metric(o.metric);
  if (!(o.ppd > 0) || !std::isfinite(o.ppd)) throw InputError("--ppd: must be a positive number");
  const bool given = o.threshold_option && o.threshold_option->count() > 0;
  const double threshold = given ? o.threshold : default_threshold(chosen);
  if (!std::isfinite(threshold) || threshold < 0) throw InputError("--threshold: must be a finite number >= 0");

  if (!o.diff.empty()) {
    check_output_paths("--diff", {o.diff}, ".exr");
    check_not_an_input("--diff", o.diff, {{"reference", o.reference}, {"test", o.test}});
  }
  const FrameImage reference = read_exr(o.reference);
  const FrameImage test = read_exr(o.test);
  const ImageLayer& ref_layer = require_layer(reference, o.layer, o.reference);
  const ImageLayer& test_layer = require_layer(test, o.layer, o.test);
  if (reference.width != test.width || reference.height != test.height)
    throw InputError(o.test + ": image is " + std::to_string(test.width) + "x" + std::to_string(test.height) +
                     " but the reference " + o.reference + " is " + std::to_string(reference.width) + "x" +
                     std::to_string(reference.height));
  require_finite(ref_layer.rgb, reference.width, o.reference, o.layer);
  require_finite(test_layer.rgb, test.width, o.test, o.layer);

  const ImageComparison c = compare_images(ref_layer.rgb, test_layer.rgb, reference.width, reference.height, o.ppd);
  std::printf("reference  %s (%dx%d, layer %s)\n", o.reference.c_str(), reference.width, reference.height,
              o.layer.c_str());
  std::printf("test       %s\n", o.test.c_str());
  for (ImageMetric m : {ImageMetric::rmse, ImageMetric::relmse, ImageMetric::mean, ImageMetric::relmae, ImageMetric::flip}) {
    if (m == chosen) continue;
    std::printf("%-7s %.6g  (%s)\n", image_metric_name(m), c.value(m), describe(m, c).c_str());
  }
  std::printf("%-7s %.6g  (%s)\n", image_metric_name(chosen), c.value(chosen), describe(chosen, c).c_str());
  const bool pass = c.value(chosen) <= threshold;
  if (o.layer == "combined") {
    const LightBias bias = light_bias(reference, test);
    std::printf("bias    %+.4f%% image mean", 100 * bias.mean);
    if (test.find("direct")) std::printf(", %+.4f%% indirect light with the direct light matched", 100 * bias.indirect);
    std::printf("\n");
  }

  if (!o.diff.empty()) {
    FrameImage map = error_map_image(c.map(chosen), c.width, c.height);
    map.attributes = {{"pmrender/compare_metric", image_metric_name(chosen)},
                      {"pmrender/compare_reference", o.reference},
                      {"pmrender/compare_test", o.test},
                      {"pmrender/compare_layer", o.layer}};
    write_exr(o.diff, map, true);
    std::printf("wrote %s (per-pixel %s error as grey)\n", o.diff.c_str(), image_metric_name(chosen));
  }
  std::printf("%s %.6g %s threshold %.6g: %s\n", image_metric_name(chosen), c.value(chosen), pass ? "<=" : ">",
              threshold, pass ? "pass" : "FAIL");
  return pass ? 0 : 1;
}

}  // namespace

Run add_compare_command(CLI::App& app) {
  auto options = std::make_shared<CompareOptions>();
  CLI::App* cmd = app.add_subcommand(
      "compare", "Compare a test image with a reference (EXR): all metrics, pass/fail on the chosen one");
  cmd->add_option("reference", options->reference, "Reference image (EXR)")->required();
  cmd->add_option("test", options->test, "Test image (EXR)")->required();
  cmd->add_option("--metric", options->metric, "flip (HDR-FLIP), rmse, relmse, mean or relmae")
      ->capture_default_str()
      ->check(CLI::IsMember({"flip", "rmse", "relmse", "mean", "relmae"}));
  options->threshold_option = cmd->add_option("--threshold", options->threshold,
                  "Pass at or under this value (default: flip 0.05, rmse 0.01, relmse 0.01, mean 0.01, relmae 0.05)")
      ->transform(finite_in(0, DBL_MAX));
  cmd->add_option("--diff", options->diff, "Write the per-pixel error of the chosen metric here (EXR, grey)");
  cmd->add_option("--layer", options->layer, "Layer to compare: combined, direct, indirect, caustic, ...")
      ->capture_default_str();
  cmd->add_option("--ppd", options->ppd, "FLIP viewing condition: pixels per degree of visual angle")
      ->capture_default_str()->transform(positive_in(DBL_MAX));
  return [options] { return run_compare(*options); };
}

}  // namespace pm::cli
