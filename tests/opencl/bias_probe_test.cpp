// The bias of final gathering over radiosity measured along the error control's paths
// (kernels/common/radiosity_bias_probe.h, render/bias_control.h paired_bias), on PoCL: in the
// spot-lit box, whose coarse solution leaves final gathering levelling off at about 3.7 %, the
// probe's signed bias is the one the film itself converges to against the same control, and its
// relative mean absolute error is the film's error once its noise is gone; a finer solution
// reads a smaller bias; a method without a probe says so.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <memory>

#include "render/bias_control.h"
#include "render/path/path_settings.h"
#include "render/radiosity/radiosity_settings.h"
#include "render/renderer.h"
#include "support/device_checks.h"
#include "support/lit_boxes.h"

namespace pm {
namespace {

Device& device() { return test::shared_opencl_device(); }

// Final gathering over the spot-lit box's solution at elements of max_edge, with the links'
// defaults.
std::shared_ptr<const MethodSettings> gathered_over(float max_edge) {
  auto r = std::make_shared<RadiositySettings>();
  r->max_edge = max_edge;
  r->bounces = 2;
  r->final_gather = 16;
  r->validate();
  return r;
}

struct Measured {
  BiasEstimate film;   // the film after its passes against the control
  BiasEstimate probe;  // the probe's reading of its bias
};

// `passes` passes of final gathering over the solution in the spot-lit box at 48 x 48, then a
// control and a probe of `paths` paths per control pixel on the same renderer.
Measured measure(const std::shared_ptr<const MethodSettings>& method, uint32_t passes, uint32_t paths) {
  RenderSettings settings;
  settings.width = settings.height = 48;
  settings.method = method;
  const Scene box = test::spot_box();
  Renderer renderer(device(), box, settings);
  renderer.begin_frame(0);
  for (uint32_t i = 0; i < passes; ++i) renderer.run_pass();
  renderer.wait();
  SharedControl control, probe;
  renderer.grow_shared_control(control, paths);
  EXPECT_TRUE(renderer.grow_bias_probe(probe, paths));
  Measured m;
  m.film = compare_with_control(control.sums, renderer.film_at_control(), renderer.error_control_grid(), control.paths,
                                kControlRegionSide, renderer.film_passes_at_control());
  m.probe = paired_bias(probe, renderer.error_control_grid(), control_level(control));
  std::printf("film after %u passes: signed %+.3f %% (+-%.3f), relMAE %.3f %%; probe: signed %+.3f %% (+-%.3f), "
              "relMAE %.3f %% (+-%.3f)\n",
              passes, 100 * m.film.signed_bias, 100 * m.film.bias_error, 100 * m.film.mean_abs_error,
              100 * m.probe.signed_bias, 100 * m.probe.bias_error, 100 * m.probe.mean_abs_error,
              100 * m.probe.mean_abs_error_stderr);
  return m;
}

TEST(BiasProbe, MeasuresTheBiasFinalGatheringOverRadiosityLevelsAt) {
  const Measured coarse = measure(test::coarse_spot_box_radiosity(16), 128, 2048);
  ASSERT_TRUE(coarse.film.known);
  ASSERT_TRUE(coarse.probe.known);
  // The signed bias: the film's, its noise averaged over the control pixels, against the probe's,
  // both read against paths of the control's stream, within three of their standard errors.
  const double spread = std::hypot(coarse.film.bias_error, coarse.probe.bias_error);
  EXPECT_GT(std::fabs(coarse.probe.signed_bias), 6 * spread) << "a bias the probe must see";
  EXPECT_NEAR(coarse.probe.signed_bias, coarse.film.signed_bias, 3 * spread + 0.002);
  // Per pixel: the film's error after 256 passes of 16 rays is its bias and what noise is left,
  // so at least the probe's and not far above it.
  EXPECT_GE(coarse.film.mean_abs_error, 0.85 * coarse.probe.mean_abs_error);
  EXPECT_LE(coarse.film.mean_abs_error, 1.3 * coarse.probe.mean_abs_error);
  // A finer solution, with the links' defaults: less bias one bounce away.
  const Measured fine = measure(gathered_over(0.05f), 4, 2048);
  EXPECT_LT(fine.probe.mean_abs_error, 0.5 * coarse.probe.mean_abs_error);
}

TEST(BiasProbe, AMethodWithoutAProbeAddsNothing) {
  RenderSettings settings;
  settings.width = settings.height = 16;
  auto traced = std::make_shared<PathSettings>();
  traced->validate();
  settings.method = traced;
  const Scene box = test::spot_box();
  Renderer renderer(device(), box, settings);
  renderer.begin_frame(0);
  renderer.run_pass();
  SharedControl probe;
  EXPECT_FALSE(renderer.grow_bias_probe(probe, 64));
  EXPECT_EQ(probe.paths, 0u);
}

}  // namespace
}  // namespace pm
