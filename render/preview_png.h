// 8-bit PNG preview of a frame (--preview), encoded with stb_image_write (Debian's libstb), so
// every build can write one. Declarations only.
#pragma once

#include <cstdint>
#include <string>

#include "render/image.h"

namespace pm {

// The preview's tone map, one linear radiance value to an 8-bit sRGB code value: exposure 1
// (no scaling), clamp to [0, 1] (negatives become black, everything at or above 1 white), then the
// sRGB transfer curve (IEC 61966-2-1: 12.92 v below 0.0031308, else 1.055 v^(1/2.4) - 0.055),
// rounded to the nearest of 0..255. A quick look, not a grade.
uint8_t preview_tone_map(float linear);

// Writes the combined layer ("") through preview_tone_map as an RGB PNG. Written like the EXR
// files: to a hidden temporary in the same folder, then renamed onto the path; missing parent
// folders are created. An image without a combined layer, or any write failure:
// pm::DeviceError naming the path.
void write_preview_png(const std::string& path, const FrameImage& image);

}  // namespace pm
