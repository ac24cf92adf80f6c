// Owns the mapping from Wavefront MTL materials to the renderer's modified-Phong MaterialDesc:
// Kd -> diffuse, Ks -> glossy, Ns -> exponent, Ke -> emission (area lights), and for illum 3/5/7 (ray-traced reflection)
// Ks -> mirror instead of glossy; map_Kd -> the base-colour texture (times Kd), map_d -> an
// alpha mask. MTL files in the wild often break energy conservation (Kd + Ks > 1), so such
// materials are scaled down rather than rejected (unlike JSON materials).
#pragma once

#include <string>
#include <vector>

#include "render/scene.h"

namespace pm {

class SceneTextures;

// A texture statement (map_Kd, map_d) as tinyobjloader read it.
struct MtlTexture {
  std::string file;          // the image as written, relative to the MTL file's folder; "" = none
  bool clamp = false;        // -clamp on: clamp to the edge instead of repeating
  char channel = 'm';        // -imfchan: r, g, b select that channel of a map_d image
};

// The MTL values the renderer uses, as tinyobjloader read them.
struct MtlMaterial {
  std::string name;
  std::string mtl_file;  // where it was defined, for messages
  float kd[3] = {0, 0, 0};
  float ks[3] = {0, 0, 0};
  float ke[3] = {0, 0, 0};  // emitted radiance, W sr^-1 m^-2 (an area light when above zero)
  float ns = 1;
  int illum = 0;
  MtlTexture map_kd, map_d;
  // Statements the material has that are not rendered ("map_bump", "map_Ks", ...), for the
  // loader's one warning per MTL file and statement.
  std::vector<std::string> ignored;
};

// The alpha cutoff of map_d masks (MTL has none of its own; glTF's default).
constexpr float kMtlAlphaCutoff = 0.5f;

// The per-channel sum diffuse + glossy + mirror that over-bright MTL materials are scaled to.
constexpr float kMtlMaxReflectance = 0.99f;

// illum 3 ("reflection on, ray trace on"), 5 (Fresnel) and 7 (refraction + reflection) are the
// illumination models that ask for a mirror reflection.
bool mtl_illum_is_mirror(int illum);

// Converts one material. Throws InputError "<mtl_file>: material '<name>': Kd[1] is negative"
// (or not finite; likewise Ks, Ns). When a channel's diffuse + glossy + mirror exceeds 1, that
// channel's terms are scaled to sum to kMtlMaxReflectance and a one-line warning is appended.
// map_Kd and map_d images are read through textures (null: the material is left untextured),
// relative to the MTL file's folder: "<mtl_file>: material '<name>': map_Kd: cannot open ...".
// map_d's mask is the image's alpha where it has one, else its first (grey or red) channel, or
// the channel -imfchan r|g|b names; points below kMtlAlphaCutoff are not there.
MaterialDesc material_from_mtl(const MtlMaterial& mtl, std::vector<std::string>* warnings, SceneTextures* textures);

}  // namespace pm
