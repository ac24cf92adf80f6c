// The exposure of PNG previews (--preview): the automatic rule that picks it from the image, and
// the range an exposure may take. Declarations only.
#pragma once

#include <vector>

namespace pm {

// Exposures are in stops: the preview shows linear radiance times 2^EV. Beyond +-32 stops no
// rendered radiance becomes visible that was not already black or white, and 2^EV stays a
// normal float.
constexpr double kMaxExposureStops = 32;

// The automatic exposure of a linear RGB image (width x height x 3 floats, interleaved): the EV
// that shows the 99th percentile of the pixels' luminance (Rec. 709: 0.2126 R + 0.7152 G +
// 0.0722 B; nearest rank) as display white, so the brightest 1 % of the image (lights, highlights)
// may clip and the rest keeps its gradation. When that percentile is black (an image dark but for
// a few pixels), the brightest pixel is used instead; a black or empty image gets EV 0. Non-finite
// and negative values count as black. The result is rounded to 1/100 stop, so the value a preview
// records reproduces it exactly, and clamped to +-kMaxExposureStops: always finite.
double automatic_exposure_ev(const std::vector<float>& rgb);

}  // namespace pm
