// FLIP, the perceptual image difference of Andersson et al. 2020 ("FLIP: A Difference Evaluator
// for Alternating Images", LDR-FLIP) and its high-dynamic-range form of Andersson et al. 2021
// ("Visualizing Errors in Rendered High Dynamic Range Images", HDR-FLIP), implemented from the
// papers' equations. Host code only; used by `pmrender compare` and the golden-image tests.
//
// LDR-FLIP of a reference R and a test T (linear RGB in [0, 1]) is, per pixel,
//   colour pipeline:  RGB -> XYZ -> YyCxCz (linearised L*a*b* opponent space, D65 white);
//                     each channel filtered with the spatial form of its contrast sensitivity
//                     function (a sum of Gaussians in visual degrees); back to linear RGB,
//                     clamped to [0, 1]; CIE L*a*b* with the Hunt adjustment (a*, b* scaled by
//                     0.01 L*); HyAB distance |dL| + ||(da, db)||; raised to q_c = 0.7 and
//                     mapped onto [0, 1] piecewise linearly so that p_c * c_max^q_c -> p_t, with
//                     p_c = 0.4, p_t = 0.95 and c_max the HyAB distance of Hunt-adjusted pure
//                     green and pure blue (the largest possible).
//   feature pipeline: luminance Y = (Yy + 16) / 116 of the unfiltered images; edges by the first
//                     and points by the second partial derivatives of a Gaussian of standard
//                     deviation 0.5 * 0.082 degrees (positive and negative weights each
//                     normalised to sum to +-1); dE_f = (max(|e_R - e_T|, |p_R - p_T|) / sqrt 2)^q_f
//                     with q_f = 0.5, e and p the gradient magnitudes.
//   combination:      dE = dE_c ^ (1 - dE_f), in [0, 1].
// HDR-FLIP tone-maps both images at exposures 2^c (c from c_start to c_stop, derived from the
// reference) with the ACES fit of Narkowicz, clamps to [0, 1], runs LDR-FLIP at each exposure and
// keeps the per-pixel maximum. The summary value is the mean over the image.
//
// Viewing conditions: an observer 0.7 m from a 0.7 m wide 3840-pixel monitor, i.e. about 67
// pixels per degree (pixels_per_degree(0.7, 3840, 0.7) = 67.02). Borders: filters clamp to the
// nearest edge pixel.
#pragma once

#include <vector>

namespace pm::flip {

// Pixels per degree of visual angle for an observer at distance_m from a monitor of width_m
// metres and width_px pixels.
double pixels_per_degree(double distance_m, double width_px, double width_m);
// The papers' default viewing conditions: 0.7 m, 3840 px, 0.7 m -> 67.02 px/degree.
double default_pixels_per_degree();

// --- colour: the building blocks, exposed for tests ----------------------------------------------
struct Color {
  float x = 0, y = 0, z = 0;
};

Color linear_rgb_to_xyz(Color rgb);  // linear sRGB (D65) -> CIE XYZ, white (1,1,1) -> D65 white
Color xyz_to_linear_rgb(Color xyz);
Color xyz_to_ycxcz(Color xyz);       // (Yy, Cx, Cz): 116 Y/Yw - 16, 500 (X/Xw - Y/Yw), 200 (Y/Yw - Z/Zw)
Color ycxcz_to_xyz(Color ycxcz);
Color xyz_to_lab(Color xyz);         // CIE 1976 L*a*b*, D65 white
Color hunt_adjust(Color lab);        // (L, 0.01 L a, 0.01 L b)
float hyab(Color lab_a, Color lab_b);  // |dL| + sqrt(da^2 + db^2)
float max_color_distance();          // c_max: HyAB of Hunt-adjusted linear green (0,1,0) and blue (0,0,1)
// HyAB distance of Hunt-adjusted colours -> colour error in [0, 1] (q_c, p_c, p_t above).
float remap_color_error(float hyab_distance);
// Feature error from the edge and point gradient magnitudes of reference and test.
float feature_error(float edge_reference, float edge_test, float point_reference, float point_test);
// The final per-pixel value: color_error ^ (1 - feature_error).
float combine_errors(float color_error, float feature_error);

// --- spatial filters ------------------------------------------------------------------------------
// One-dimensional factors of a separable 2-D kernel, radius r (2r + 1 taps each).
struct SeparableTerm {
  float weight = 0;  // the 2-D kernel is sum of weight * x_taps (outer) y_taps over its terms
  std::vector<float> x_taps, y_taps;
};
using SeparableKernel = std::vector<SeparableTerm>;
// Contrast sensitivity filters for channel 0 (achromatic Yy), 1 (red-green Cx), 2 (blue-yellow
// Cz), normalised to sum to 1 over the 2-D kernel. Radius ceil(3 sqrt(b_max / (2 pi^2)) ppd).
SeparableKernel csf_kernel(int channel, double ppd);
// Feature detectors: edge_kernel(dx=1,dy=0) is d/dx of the Gaussian, point is d2/dx2.
SeparableKernel edge_kernel(double ppd, bool along_x);
SeparableKernel point_kernel(double ppd, bool along_x);
// Convolves a width x height single-channel image, clamping at the borders.
std::vector<float> convolve(const std::vector<float>& image, int width, int height, const SeparableKernel& kernel);

// --- whole images ------------------------------------------------------------------------------
// LDR-FLIP per pixel of linear RGB images (width*height*3, values clamped to [0, 1] first).
std::vector<float> ldr_flip(const std::vector<float>& reference, const std::vector<float>& test, int width,
                            int height, double ppd);

// The ACES filmic fit of Narkowicz 2015, with his 0.6 pre-exposure folded in, clamped to [0, 1]:
// t(x) = (0.6^2 2.51 x^2 + 0.6 0.03 x) / (0.6^2 2.43 x^2 + 0.6 0.59 x + 0.14).
float tone_map(float x);
// x with tone_map(x) = y, for y in [0, 1).
float inverse_tone_map(float y);

struct ExposureRange {
  double start = 0;  // c_start = log2(t^-1(0.85) / L_max): the brightest pixel just below white
  double stop = 0;   // c_stop = log2(t^-1(0.85) / L_median): the median pixel just below white
  int count = 2;     // max(2, ceil(c_stop - c_start)) exposures, evenly spaced from start to stop
};
// From the reference's luminance (0.2126 R + 0.7152 G + 0.0722 B). When more than half of the
// pixels are black, the median of the non-black pixels is used; an all-black reference gives the
// single exposure 0 (twice).
ExposureRange exposure_range(const std::vector<float>& reference_rgb);

struct HdrFlipResult {
  std::vector<float> error;  // per pixel, in [0, 1]
  double mean = 0;           // the summary value
  ExposureRange exposures;
};
// HDR-FLIP of linear HDR images (width*height*3 floats, finite).
HdrFlipResult hdr_flip(const std::vector<float>& reference, const std::vector<float>& test, int width, int height,
                       double ppd);

}  // namespace pm::flip
