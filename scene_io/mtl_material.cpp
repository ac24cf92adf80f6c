// Owns MTL -> MaterialDesc conversion (see mtl_material.h): validation of Kd/Ks/Ns, the illum
// mirror rule and the scaling of over-bright materials.
#include "scene_io/mtl_material.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "scene_io/load_error.h"
#include "scene_io/texture_files.h"

namespace pm {
namespace {

const char* const kChannelNames[3] = {"red", "green", "blue"};

void check_non_negative(const MtlMaterial& mtl, const char* field, const float* values, int count) {
  for (int i = 0; i < count; ++i) {
    std::string problem;
    if (!std::isfinite(values[i])) {
      problem = "is not a finite number";
    } else if (values[i] < 0) {
      problem = "is negative";
    } else {
      continue;
    }
    std::string name = field;
    if (count > 1) name += "[" + std::to_string(i) + "]";
    throw_input_error(mtl.mtl_file + ": material '" + mtl.name + "'", name + " " + problem);
  }
}

float& channel(Float3& c, int i) { return i == 0 ? c.x : (i == 1 ? c.y : c.z); }

// The texture of a map_Kd or map_d statement, its file relative to the MTL file's folder.
int mtl_texture(const MtlMaterial& mtl, const MtlTexture& texture, const char* statement, SceneTextures* textures) {
  namespace fs = std::filesystem;
  const fs::path file = fs::path(texture.file).is_absolute() ? fs::path(texture.file)
                                                             : fs::path(mtl.mtl_file).parent_path() / texture.file;
  const TextureWrap wrap = texture.clamp ? TextureWrap::clamp_to_edge : TextureWrap::repeat;
  return textures->file_texture(file.string(), texture.file,
                                mtl.mtl_file + ": material '" + mtl.name + "': " + statement, wrap, wrap);
}

}  // namespace

bool mtl_illum_is_mirror(int illum) { return illum == 3 || illum == 5 || illum == 7; }

MaterialDesc material_from_mtl(const MtlMaterial& mtl, std::vector<std::string>* warnings, SceneTextures* textures) {
  check_non_negative(mtl, "Kd", mtl.kd, 3);
  check_non_negative(mtl, "Ks", mtl.ks, 3);
  check_non_negative(mtl, "Ns", &mtl.ns, 1);
  check_non_negative(mtl, "Ke", mtl.ke, 3);

  MaterialDesc desc;
  desc.name = mtl.name;
  desc.diffuse = Float3{mtl.kd[0], mtl.kd[1], mtl.kd[2]};
  const Float3 specular{mtl.ks[0], mtl.ks[1], mtl.ks[2]};
  if (mtl_illum_is_mirror(mtl.illum)) {
    desc.glossy = Float3{0, 0, 0};
    desc.mirror = specular;
  } else {
    desc.glossy = specular;
    desc.mirror = Float3{0, 0, 0};
  }
  desc.glossy_exponent = mtl.ns;
  desc.emission = Float3{mtl.ke[0], mtl.ke[1], mtl.ke[2]};
  if (textures && !mtl.map_kd.file.empty()) desc.base_color_texture = mtl_texture(mtl, mtl.map_kd, "map_Kd", textures);
  if (textures && !mtl.map_d.file.empty()) {
    desc.alpha_mask = true;
    desc.alpha_texture = mtl_texture(mtl, mtl.map_d, "map_d", textures);
    desc.alpha_cutoff = kMtlAlphaCutoff;
    const char c = mtl.map_d.channel;
    if (c == 'r' || c == 'g' || c == 'b') {
      desc.alpha_channel = c == 'r' ? 0 : c == 'g' ? 1 : 2;
    } else {
      const int channels = textures->image_of(desc.alpha_texture).file_channels;
      desc.alpha_channel = channels == 2 || channels == 4 ? 3 : 0;
    }
  }

  // Per channel, so a saturated red wall keeps its green and blue untouched.
  std::string scaled_channels;
  for (int c = 0; c < 3; ++c) {
    float sum = channel(desc.diffuse, c) + channel(desc.glossy, c) + channel(desc.mirror, c);
    if (sum <= 1.0f + 1e-6f) continue;  // float rounding: 0.6 + 0.4 may exceed 1 by an ulp
    float scale = kMtlMaxReflectance / sum;
    channel(desc.diffuse, c) *= scale;
    channel(desc.glossy, c) *= scale;
    channel(desc.mirror, c) *= scale;
    std::ostringstream note;
    note << kChannelNames[c] << " " << sum;
    scaled_channels += (scaled_channels.empty() ? "" : ", ") + note.str();
  }
  if (!scaled_channels.empty() && warnings) {
    warnings->push_back(single_line(mtl.mtl_file + ": material '" + mtl.name +
                                    "': reflectance sum above 1 (" + scaled_channels +
                                    ") scaled down to 0.99"));
  }
  return desc;
}

}  // namespace pm
