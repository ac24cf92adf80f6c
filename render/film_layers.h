// The film's extra layers for compositing and denoising (docs/layers.md): which ones a render asks
// for, their names on the command line and in the EXR file, and their read-back from the device
// buffers kernels/common/film_layers.h fills into a FrameImage. The renderer allocates and fills
// them only when asked, so a frame without them is what it always was.
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "render/image.h"
#include "render/kernel_abi.h"
#include "render/named_values.h"
#include "render/scene.h"

namespace pm {

enum class FilmLayer : int { albedo, normal, depth, position, object_id, material_id };

// Layer names as `--layers` spells them, in the order the file lists them.
const NameTable& film_layer_names();

// A set of extra layers; empty by default.
struct FilmLayers {
  uint32_t bits = 0;
  bool empty() const { return bits == 0; }
  bool has(FilmLayer layer) const { return (bits >> int(layer)) & 1u; }
  void add(FilmLayer layer) { bits |= 1u << int(layer); }
  bool operator==(const FilmLayers& other) const { return bits == other.bits; }
};

// "albedo,normal" -> that set; "all" -> every layer; "" or "none" -> no layer. Names may repeat;
// spaces around them are ignored. Throws SettingError("layers", ...) naming the unknown name.
FilmLayers parse_film_layers(const std::string& list);
// The set as a comma list in file order ("" for none), the form parse_film_layers reads.
std::string film_layers_text(const FilmLayers& layers);

// The device buffers' contents (one float4 per pixel each, kernels/common/film_layers.h) as the
// image's layers: albedo as the RGB layer "albedo", the others as data layers (N.X, Z, P.X,
// object_id.X, material_id.X). Ids are written as 32-bit floats whatever the file's pixel type.
void add_film_layers(FrameImage& image, const FilmLayers& layers, const std::vector<float4>& albedo,
                     const std::vector<float4>& normal, const std::vector<float4>& position);

// Header attributes saying which layers the file holds and in which channels ("pmrender/layers":
// "albedo:albedo.R,albedo.G,albedo.B depth:Z ..."), the depth a miss reads as in a file of this
// pixel type ("pmrender/depth_miss"), and which object or material each id is
// ("pmrender/object_ids", "pmrender/material_ids": "0=name; 1=name"). None without layers.
std::vector<std::pair<std::string, std::string>> film_layer_attributes(const FilmLayers& layers, const Scene& scene,
                                                                       bool full_float);

}  // namespace pm
