// The in-memory form of one rendered frame as it goes to (and comes back from) an image file:
// named RGB layers plus string metadata. Plain data only, no OpenEXR types, so any host file can
// include it. (Never include OpenEXR from here: Imath's half clashes with CUDA's in .cu files.)
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pm {

// One RGB layer. rgb holds width*height*3 floats, row-major, top row first, R G B interleaved.
// The empty name is the combined image (EXR channels R, G, B); any other name becomes the
// channel prefix ("direct" -> direct.R, direct.G, direct.B).
struct ImageLayer {
  std::string name;
  std::vector<float> rgb;
};

struct FrameImage {
  int width = 0;
  int height = 0;
  std::vector<ImageLayer> layers;
  // Extra string attributes for the file header, e.g. {"pmrender/scene", "cornell-box"}.
  std::vector<std::pair<std::string, std::string>> attributes;

  // The layer with this name, or nullptr. find("") is the combined image.
  const ImageLayer* find(const std::string& name) const {
    for (const ImageLayer& layer : layers) {
      if (layer.name == name) return &layer;
    }
    return nullptr;
  }
};

}  // namespace pm
