// The bias part of a frame's error estimate: sparse path-traced control pixels compared with
// the film (kernels/common/bias_control.h). The even/odd estimate of the film (film.h) sees
// noise only: a photon map whose footprints lose light over edges reads 0.3 % while its image
// is 17 % too dark. The control is an unbiased sample of the true image at one pixel per block,
// so the film's deviation from it there, less the control's own noise, is the bias that a user
// trading speed for accuracy must be told about.
#pragma once

#include <cstdint>
#include <functional>
#include <vector>

#include "render/kernel_abi.h"

namespace pm {

class BufferTable;
class Device;

// What the control says about the film, relative to the mean indirect light of the control
// pixels. With d_c = film - control mean and v_c the variance of the control's mean at control
// pixel c, E[d_c^2 - v_c] is the film's mean squared error there, noise and bias together: the
// control measures the film's whole error, for any method, from one pass on.
struct BiasEstimate {
  double mean_abs_error = 0;   // the film's relative mean absolute error (bias and noise): per control
                               // pixel the |e| whose E|e + control noise| is the observed |d_c|, or
                               // where the control's noise exceeds the film's error, per region
                               // from its second moments (bias_control.cpp), summed over the
                               // control mean; plus its standard error (over the regions)
  double mean_abs_error_upper = 0; // the same with two standard errors (the stopping rule's)
  double mean_abs_error_stderr = 0; // that standard error
  double mean_square = 0;      // mean(d_c^2 - v_c) / mean control^2: unbiased for the film's relative MSE
  double rms_error = 0;        // sqrt(mean(d_c^2 - v_c) + its standard error) / mean control: the
                               // film's relative RMS error (an unbiased mean square)
  double signed_bias = 0;     // (film - control) summed over every control pixel / control sum
  double bias_error = 0;      // the standard error of signed_bias from the control's paths
  double regional_bias = 0;   // sum over regions of |film - control|, less the control's noise there
  double control_noise = 0;   // the control's own standard error per pixel, mean over pixels / mean control
  uint64_t paths = 0;         // paths per control pixel so far
  // The part of mean_abs_error that the film's own noise does not explain, at least: with the
  // film's even and odd passes at each control pixel (ControlFilmPasses), E[d_c^2 - v_c - n_c]
  // is its squared bias there (n_c: the film's own variance from its even/odd split); its mean,
  // less two standard errors, over the mean of d_c^2 - v_c, as a share of the relative mean
  // absolute error. What more passes of a method whose passes are independent samples of one
  // estimate cannot remove (docs/method-auto.md, "The duel"). Two standard errors, not one: with
  // one taken off, early readings on Sponza read floors of a quarter of their error that the next
  // doubling of passes took back (final gathering over photons 2.52 % at 10.19 % after 8 passes,
  // then 0.11 %; over radiosity 2.61 % at 8.41 %, whose later readings show about 0.8 %).
  // -1: not known.
  double bias_floor = -1;
  // The same with two standard errors added: the part that is bias, at most. -1: not known.
  double bias_ceiling = -1;
  bool known = false;         // false: no control ran, or the control saw no light
};

// The passes behind a control film, for bias_floor: its w holds the odd passes' mean there.
struct ControlFilmPasses {
  uint32_t passes = 0;
  uint32_t odd = 0;  // of passes, those with an odd pass number
  bool split() const { return odd > 0 && odd < passes; }
};

// The control pixel grid of a film: one pixel per stride x stride block, stride chosen so that
// a frame has at most about kControlPixelsTarget of them. Few pixels with many paths each: the
// film's error at a control pixel is read against the control's own noise there, and where
// that noise exceeds the error the reading is poor (a closed box lit by a small lamp, whose
// paths are heavy-tailed: with 128 paths over 8192 pixels the estimate read 6 times the true
// error, docs/accuracy.md); the mean over a couple of thousand pixels is already precise.
struct ControlGrid {
  uint32_t stride = 1;
  uint32_t blocks_x = 0, blocks_y = 0;
  uint64_t pixels() const { return uint64_t(blocks_x) * blocks_y; }
};
constexpr uint32_t kControlPixelsTarget = 1024;
// Control pixels per region side: regions of 4 x 4 control pixels (about 64 x 64 pixels of a
// 960 x 540 film) are where a bias is looked for (an edge's, a corner's).
constexpr uint32_t kControlRegionSide = 4;
// Paths per control pixel added by each estimate while a frame goes on (a target error asks
// after every pass).
constexpr uint32_t kControlPathsPerStep = 64;
// The most paths per control pixel a frame's final estimate may grow to, in control_paths: it
// grows while the control's own noise per pixel exceeds the error it reads.
constexpr uint32_t kControlPathsGrowth = 16;
ControlGrid control_grid(int width, int height);

// Deviation of the film from the control, from the per-control-pixel sums (control_sums /
// control_film as the kernel writes them). Regions are groups of region_side x region_side
// control pixels: within one, the film's bias is summed before its absolute value is taken,
// and the control's variance there is subtracted from the square (an unbiased |bias|^2).
// level_of: the mean light per control pixel the relative figures are of, where not the
// control's own (paired_bias: sums of differences, whose mean is near zero).
BiasEstimate compare_with_control(const std::vector<float4>& control_sums, const std::vector<float4>& control_film,
                                  const ControlGrid& grid, uint64_t paths, uint32_t region_side,
                                  ControlFilmPasses film_passes = {}, double level_of = 0);

// A control shared by several renderers of one frame (--method auto's race,
// render/method_race.h): its paths depend only on the frame, the seed and the bounces, so one set
// of control paths measures every candidate's film, and grows on whichever renderer is at hand.
struct SharedControl {
  std::vector<float4> sums;  // control_sums as the kernel leaves them; empty: no paths yet
  uint64_t paths = 0;        // per control pixel
  uint32_t bounces = 0;      // the light bounces its paths follow
};

// The mean light per control pixel of a control's paths (its channel mean); 0 with no paths.
double control_level(const SharedControl& control);
// A method's bias measured along the control's paths (IndirectMethod::launch_bias_probe: per
// path, the path's estimate less the method's along the path's first direction): its relative
// mean absolute error (mean_abs_error, with one standard error; mean_abs_error_stderr), read per
// control pixel through the differences' own noise and per region where that noise is the larger,
// as compare_with_control reads a film, relative to `level` (control_level of the frame's control).
BiasEstimate paired_bias(const SharedControl& probe, const ControlGrid& grid, double level);

// Runs the control beside a renderer's film: clears it per frame, adds paths on demand.
class BiasControl {
 public:
  BiasControl(Device& device, BufferTable& buffers, int width, int height);
  // A new frame: no paths yet.
  void begin_frame() { paths_ = 0; cleared_ = false; }
  // `samples` more paths per control pixel under `params` (the frame's, with the method's
  // bounces and the film's pass count), then the comparison. Waits for the device.
  // With film_passes (params.film_odd_passes set to its odd count), the estimate's bias_floor too.
  BiasEstimate add_and_compare(LaunchParams params, uint32_t samples, ControlFilmPasses film_passes = {});
  const ControlGrid& grid() const { return grid_; }
  uint64_t paths() const { return paths_; }
  // `samples` more paths per control pixel added to shared (on this device, under params).
  // How a control pixel's paths are launched: the control's own (bias_control) where empty, or a
  // method's probe (launch_bias_probe), given the launch's parameters and work items.
  using PathsLaunch = std::function<void(const LaunchParams&, uint64_t)>;
  // With paths, the probe's sums grow instead (paired_bias reads them).
  void grow_shared(LaunchParams params, SharedControl& shared, uint32_t samples, const PathsLaunch& paths = {});
  // shared's paths become this control's (the frame's, on this renderer from now on).
  void adopt(const SharedControl& shared);
  // This film (params.film_passes) at the control pixels, as compare_with_control reads it.
  // Waits for the device.
  std::vector<float4> film_at_control(LaunchParams params);

 private:
  // samples paths per control pixel (paths first_sample... of its stream), shared out over up to
  // PM_CONTROL_LANES work items each, added to control_sums; then the film read at the pixels.
  void launch(LaunchParams params, uint32_t samples, uint64_t first_sample, const PathsLaunch& paths = {});

  Device& device_;
  BufferTable& buffers_;
  ControlGrid grid_;
  uint64_t paths_ = 0;
  bool cleared_ = false;
};

}  // namespace pm
