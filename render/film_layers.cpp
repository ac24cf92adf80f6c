// The film's extra layers: the names `--layers` accepts, their EXR channels, their read-back into
// a FrameImage, and the header attributes that list them (docs/layers.md has the mapping to
// Blender's and Nuke's names).
#include "render/film_layers.h"

#include <sstream>

#include "kernels/common/film_layers.h"
#include "render/errors.h"

namespace pm {

namespace {

// The EXR channels of each layer, in the file's words: compositors read "Z" as depth (Nuke's
// depth.Z, Blender's Depth), N and P are the usual names of normal and position passes.
struct LayerChannels {
  FilmLayer layer;
  const char* prefix;
  std::vector<std::string> channels;
};

const std::vector<LayerChannels>& layer_channels() {
  static const std::vector<LayerChannels> table = {
      {FilmLayer::albedo, "albedo", {"R", "G", "B"}},   {FilmLayer::normal, "N", {"X", "Y", "Z"}},
      {FilmLayer::depth, "", {"Z"}},                    {FilmLayer::position, "P", {"X", "Y", "Z"}},
      {FilmLayer::object_id, "object_id", {"X"}},       {FilmLayer::material_id, "material_id", {"X"}},
  };
  return table;
}

std::string channel_list(const LayerChannels& c) {
  std::string list;
  for (const std::string& channel : c.channels)
    list += (list.empty() ? "" : ",") + (*c.prefix ? std::string(c.prefix) + "." : std::string()) + channel;
  return list;
}

constexpr float kLargestHalf = 65504.0f;

// Integer ids come from the device as int bits; as floats they are exact up to 2^24.
float id_value(float bits) { return float(PM_AS_INT(bits)); }

// "0=name; 1=name", the names as loaded.
std::string id_list(const std::vector<std::string>& names) {
  std::string list;
  for (size_t i = 0; i < names.size(); ++i) list += (i ? "; " : "") + std::to_string(i) + "=" + names[i];
  return list;
}

}  // namespace

const NameTable& film_layer_names() {
  static const NameTable table = {{"albedo", int(FilmLayer::albedo)},       {"normal", int(FilmLayer::normal)},
                                  {"depth", int(FilmLayer::depth)},         {"position", int(FilmLayer::position)},
                                  {"object_id", int(FilmLayer::object_id)}, {"material_id", int(FilmLayer::material_id)}};
  return table;
}

FilmLayers parse_film_layers(const std::string& list) {
  FilmLayers layers;
  std::stringstream in(list);
  std::string item;
  bool any = false;
  while (std::getline(in, item, ',')) {
    any = true;
    const size_t begin = item.find_first_not_of(' '), end = item.find_last_not_of(' ');
    const std::string name = begin == std::string::npos ? "" : item.substr(begin, end - begin + 1);
    int value = 0;
    if (name == "all") {
      for (const NamedValue& v : film_layer_names()) layers.add(FilmLayer(v.value));
    } else if (name == "none" && list.find(',') == std::string::npos) {
      // no extra layers, as without the option
    } else if (!value_of(film_layer_names(), name, &value)) {
      throw SettingError("layers", "unknown layer '" + name + "' in '" + list + "'; expected a comma list of " +
                                       names_list(film_layer_names()) + ", or all");
    } else {
      layers.add(FilmLayer(value));
    }
  }
  if (any && !list.empty() && list.back() == ',')
    throw SettingError("layers", "empty item after the last comma in '" + list + "'");
  return layers;
}

std::string film_layers_text(const FilmLayers& layers) {
  std::string text;
  for (const NamedValue& v : film_layer_names())
    if (layers.has(FilmLayer(v.value))) text += (text.empty() ? "" : ",") + std::string(v.name);
  return text;
}

void add_film_layers(FrameImage& image, const FilmLayers& layers, const std::vector<float4>& albedo,
                     const std::vector<float4>& normal, const std::vector<float4>& position) {
  const size_t pixels = size_t(image.width) * size_t(image.height);
  if (albedo.size() != pixels || normal.size() != pixels || position.size() != pixels)
    throw DeviceError("film layers: buffers of another size than the image");
  for (const LayerChannels& c : layer_channels()) {
    if (!layers.has(c.layer)) continue;
    if (c.layer == FilmLayer::albedo) {
      ImageLayer& layer = image.layers.emplace_back(ImageLayer{c.prefix, std::vector<float>(3 * pixels)});
      for (size_t i = 0; i < pixels; ++i) {
        layer.rgb[3 * i + 0] = albedo[i].x;
        layer.rgb[3 * i + 1] = albedo[i].y;
        layer.rgb[3 * i + 2] = albedo[i].z;
      }
      continue;
    }
    DataLayer& layer = image.data_layers.emplace_back();
    layer.name = c.prefix;
    layer.channels = c.channels;
    layer.full_float = c.layer == FilmLayer::object_id || c.layer == FilmLayer::material_id;
    layer.values.resize(c.channels.size() * pixels);
    float* out = layer.values.data();
    for (size_t i = 0; i < pixels; ++i) {
      switch (c.layer) {
        case FilmLayer::normal: *out++ = normal[i].x; *out++ = normal[i].y; *out++ = normal[i].z; break;
        case FilmLayer::depth: *out++ = normal[i].w; break;
        case FilmLayer::position: *out++ = position[i].x; *out++ = position[i].y; *out++ = position[i].z; break;
        case FilmLayer::object_id: *out++ = id_value(position[i].w); break;
        case FilmLayer::material_id: *out++ = id_value(albedo[i].w); break;
        case FilmLayer::albedo: break;
      }
    }
  }
}

std::vector<std::pair<std::string, std::string>> film_layer_attributes(const FilmLayers& layers, const Scene& scene,
                                                                       bool full_float) {
  std::vector<std::pair<std::string, std::string>> attributes;
  if (layers.empty()) return attributes;
  std::string list;
  for (const LayerChannels& c : layer_channels())
    if (layers.has(c.layer))
      list += (list.empty() ? "" : " ") + std::string(name_of(film_layer_names(), int(c.layer))) + ":" + channel_list(c);
  attributes.push_back({"pmrender/layers", list});
  if (layers.has(FilmLayer::depth)) {
    // What a miss reads as in this file: half channels clamp the value to the largest half.
    std::ostringstream miss;
    miss << (full_float ? PM_LAYER_MISS_DEPTH : kLargestHalf);
    attributes.push_back({"pmrender/depth_miss", miss.str()});
  }
  if (layers.has(FilmLayer::object_id)) {
    // Triangles without an object of their own are the object after the named ones (scene.h).
    std::vector<std::string> names = scene.object_names;
    if (scene.triangle_object.size() < scene.triangle_count()) names.push_back(names.empty() ? scene.name : "unnamed");
    attributes.push_back({"pmrender/object_ids", id_list(names)});
  }
  if (layers.has(FilmLayer::material_id)) {
    std::vector<std::string> names;
    for (const MaterialDesc& m : scene.materials) names.push_back(m.name);
    attributes.push_back({"pmrender/material_ids", id_list(names)});
  }
  return attributes;
}

}  // namespace pm
