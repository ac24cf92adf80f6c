// Owns the mapping from Wavefront MTL materials to the renderer's modified-Phong MaterialDesc:
// Kd -> diffuse, Ks -> glossy, Ns -> exponent, and for illum 3/5/7 (ray-traced reflection)
// Ks -> mirror instead of glossy. MTL files in the wild often break energy conservation
// (Kd + Ks > 1), so such materials are scaled down rather than rejected (unlike JSON materials).
#pragma once

#include <string>
#include <vector>

#include "render/scene.h"

namespace pm {

// The MTL values the renderer uses, as tinyobjloader read them.
struct MtlMaterial {
  std::string name;
  std::string mtl_file;  // where it was defined, for messages
  float kd[3] = {0, 0, 0};
  float ks[3] = {0, 0, 0};
  float ns = 1;
  int illum = 0;
};

// The per-channel sum diffuse + glossy + mirror that over-bright MTL materials are scaled to.
constexpr float kMtlMaxReflectance = 0.99f;

// illum 3 ("reflection on, ray trace on"), 5 (Fresnel) and 7 (refraction + reflection) are the
// illumination models that ask for a mirror reflection.
bool mtl_illum_is_mirror(int illum);

// Converts one material. Throws InputError "<mtl_file>: material '<name>': Kd[1] is negative"
// (or not finite; likewise Ks, Ns). When a channel's diffuse + glossy + mirror exceeds 1, that
// channel's terms are scaled to sum to kMtlMaxReflectance and a one-line warning is appended.
MaterialDesc material_from_mtl(const MtlMaterial& mtl, std::vector<std::string>* warnings);

}  // namespace pm
