// 8-bit PNG preview of a frame (--preview), encoded with stb_image_write (Debian's libstb), so
// every build can write one; the exposure it was made with is recorded in the file's text.
// Declarations only.
#pragma once

#include <cstdint>
#include <optional>
#include <string>

#include "render/image.h"

namespace pm {

// The preview's tone map, one linear radiance value to an 8-bit sRGB code value: times `scale`
// (2^EV of the exposure), clamp to [0, 1] (negatives become black, everything at or above 1
// white), then the sRGB transfer curve (IEC 61966-2-1: 12.92 v below 0.0031308, else
// 1.055 v^(1/2.4) - 0.055), rounded to the nearest of 0..255. A quick look, not a grade.
uint8_t preview_tone_map(float linear, float scale);

// PNG text keywords of a preview: the exposure in stops, and where it came from ("automatic"
// with its rule, or "--exposure").
extern const char kPreviewExposureKeyword[];
extern const char kPreviewExposureSourceKeyword[];

// Writes the combined layer ("") through preview_tone_map as an RGB PNG, at exposure_ev stops
// (within +-kMaxExposureStops) or, without one, automatic_exposure_ev of that layer
// (preview_exposure.h). Returns the exposure used, which the PNG's text records. Written like the
// EXR files: to a hidden temporary in the same folder, then renamed onto the path; missing parent
// folders are created. An image without a combined layer, an exposure out of range, or any write
// failure: pm::DeviceError naming the path.
double write_preview_png(const std::string& path, const FrameImage& image,
                         std::optional<double> exposure_ev = std::nullopt);

}  // namespace pm
