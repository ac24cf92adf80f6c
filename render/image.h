// The in-memory form of one rendered frame as it goes to (and comes back from) an image file:
// named RGB layers, data layers of any channels (normals, depth, ids) and string metadata. Plain
// data only, no OpenEXR types, so any host file can include it. (Never include OpenEXR from
// here: Imath's half clashes with CUDA's in .cu files.)
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

// One layer of non-colour data: its own channel names ("X", "Y", "Z"; "Z" alone for depth).
// values holds width*height*channels.size() floats, row-major, channels interleaved. The name
// becomes the channel prefix ("N" -> N.X, N.Y, N.Z); the empty name gives bare channels ("Z").
struct DataLayer {
  std::string name;
  std::vector<std::string> channels;
  std::vector<float> values;
  // Always 32-bit float in the file, even where colour layers are half: integer ids (half holds
  // integers exactly only up to 2048). Read back: every channel of the layer is float.
  bool full_float = false;

  // "N.X", or "Z" for the empty name.
  std::string channel_name(size_t channel) const {
    return name.empty() ? channels[channel] : name + "." + channels[channel];
  }
};

struct FrameImage {
  int width = 0;
  int height = 0;
  std::vector<ImageLayer> layers;
  std::vector<DataLayer> data_layers;  // written after the colour layers; none by default
  // Extra string attributes for the file header, e.g. {"pmrender/scene", "cornell-box"}.
  std::vector<std::pair<std::string, std::string>> attributes;

  // The layer with this name, or nullptr. find("") is the combined image.
  const ImageLayer* find(const std::string& name) const {
    for (const ImageLayer& layer : layers) {
      if (layer.name == name) return &layer;
    }
    return nullptr;
  }
  // The data layer with this name, or nullptr; find_data("") holds bare channels such as "Z".
  const DataLayer* find_data(const std::string& name) const {
    for (const DataLayer& layer : data_layers) {
      if (layer.name == name) return &layer;
    }
    return nullptr;
  }
};

}  // namespace pm
