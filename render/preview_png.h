// Optional 8-bit PNG preview of a frame (--preview), written with OpenImageIO when the build has
// it (PMRENDER_HAVE_OIIO). Declarations only; OpenImageIO stays inside preview_png.cpp.
#pragma once

#include <string>

#include "render/image.h"

namespace pm {

// True when this build can write previews (it was built with OpenImageIO).
bool preview_available();

// Writes the combined layer ("") as an 8-bit sRGB PNG: exposure 1, clamped to [0, 1], sRGB
// transfer curve; no further tone mapping, so it is a quick look, not a grade. Written like the
// EXR files: to a hidden temporary in the same folder, then renamed onto the path; missing parent
// folders are created.
// Without OpenImageIO: pm::InputError("--preview needs OpenImageIO, which this build does not
// have"). An image without a combined layer, or any write failure: pm::DeviceError naming path.
void write_preview_png(const std::string& path, const FrameImage& image);

}  // namespace pm
