// The glTF loader's textures (scene_io/gltf_loader.h): a material's baseColorTexture and its
// sampler's wrap modes, the images they name (decoded once, only when a used material names
// them), alphaMode MASK, and the TEXCOORD_n attribute a textured primitive is read with.
#include <cmath>
#include <filesystem>

#include "scene_io/gltf_loader.h"
#include "scene_io/load_error.h"
#include "scene_io/regular_files.h"
#include "scene_io/texture_files.h"

namespace pm::gltf {

namespace {

TextureWrap wrap_mode(int gltf_wrap) {
  if (gltf_wrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE) return TextureWrap::clamp_to_edge;
  if (gltf_wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT) return TextureWrap::mirrored_repeat;
  return TextureWrap::repeat;
}

bool is_wrap_mode(int gltf_wrap) {
  return gltf_wrap == TINYGLTF_TEXTURE_WRAP_REPEAT || gltf_wrap == TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE ||
         gltf_wrap == TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT;
}

}  // namespace

uint32_t GltfLoader::decoded_image(int index, const std::string& where) {
  if (index < 0 || size_t(index) >= model_.images.size())
    fail(where, "image index " + std::to_string(index) + " out of range (" + std::to_string(model_.images.size()) +
                    " images)");
  auto known = image_index_.find(index);
  if (known != image_index_.end()) return known->second;
  const tinygltf::Image& image = model_.images[size_t(index)];
  const std::string at = indexed("images", size_t(index));
  std::vector<unsigned char> view_bytes;
  const std::vector<unsigned char>* bytes = &image.image;  // a URI's bytes, kept by the image callback
  std::string field = at + ".uri", shown = image.uri;
  if (image.bufferView >= 0) {
    field = at + ".bufferView";
    shown = "bufferViews[" + std::to_string(image.bufferView) + "]";
    if (size_t(image.bufferView) >= model_.bufferViews.size()) fail(field, "bufferView index out of range");
    const tinygltf::BufferView& view = model_.bufferViews[size_t(image.bufferView)];
    if (view.buffer < 0 || size_t(view.buffer) >= model_.buffers.size()) fail(field, "bufferView has no valid buffer");
    const std::vector<unsigned char>& data = model_.buffers[size_t(view.buffer)].data;
    if (view.byteOffset > data.size() || view.byteLength > data.size() - view.byteOffset)
      fail(field, "the bufferView reaches past the end of its buffer");
    view_bytes.assign(data.begin() + std::ptrdiff_t(view.byteOffset),
                      data.begin() + std::ptrdiff_t(view.byteOffset + view.byteLength));
    bytes = &view_bytes;
  } else if (image.uri.rfind("data:", 0) == 0) {
    shown = "data URI";
  } else if (bytes->empty()) {
    // tinygltf could not read the file (it only warns): say which file and why.
    namespace fs = std::filesystem;
    const fs::path file = fs::path(image.uri).is_absolute() ? fs::path(image.uri) : fs::path(path_).parent_path() / image.uri;
    off_t size = 0;
    std::string problem = file_problem(file.string(), &size);
    if (problem.empty()) problem = size == 0 ? "is empty" : "cannot be read";
    fail(field, "'" + image.uri + "' " + problem + (problem == "not found" ? " (looked for '" + file.string() + "')" : ""));
  }
  TextureImage decoded = decode_texture_image(bytes->data(), bytes->size(), shown, path_ + ": " + field);
  decoded.source = path_ + ": " + at;
  const uint32_t scene_image = textures_->add_image(std::move(decoded));
  image_index_[index] = scene_image;
  return scene_image;
}

int GltfLoader::texture_of(const tinygltf::TextureInfo& info, const std::string& where) {
  if (size_t(info.index) >= model_.textures.size())
    fail(where + ".index", "texture index " + std::to_string(info.index) + " out of range (" +
                               std::to_string(model_.textures.size()) + " textures)");
  const tinygltf::Texture& texture = model_.textures[size_t(info.index)];
  const std::string at = indexed("textures", size_t(info.index));
  if (texture.source < 0) {
    warn(at + ": no source image (texture extensions such as KHR_texture_basisu are not supported); the texture is ignored");
    return -1;
  }
  TextureWrap wrap_u = TextureWrap::repeat, wrap_v = TextureWrap::repeat;
  if (texture.sampler >= 0) {
    if (size_t(texture.sampler) >= model_.samplers.size())
      fail(at + ".sampler", "sampler index " + std::to_string(texture.sampler) + " out of range");
    const tinygltf::Sampler& sampler = model_.samplers[size_t(texture.sampler)];
    const std::string sampler_at = indexed("samplers", size_t(texture.sampler));
    if (!is_wrap_mode(sampler.wrapS)) fail(sampler_at + ".wrapS", "unknown wrap mode " + std::to_string(sampler.wrapS));
    if (!is_wrap_mode(sampler.wrapT)) fail(sampler_at + ".wrapT", "unknown wrap mode " + std::to_string(sampler.wrapT));
    wrap_u = wrap_mode(sampler.wrapS);
    wrap_v = wrap_mode(sampler.wrapT);
  }
  const uint32_t image = decoded_image(texture.source, at + ".source");
  return textures_->image_texture(image, wrap_u, wrap_v);
}

void GltfLoader::add_material_textures(int index, MaterialDesc* desc, std::vector<std::string>* ignored) {
  const tinygltf::Material& m = model_.materials[size_t(index)];
  const std::string where = indexed("materials", size_t(index));
  const tinygltf::TextureInfo& base = m.pbrMetallicRoughness.baseColorTexture;
  int texcoord = -1;
  if (base.index >= 0) {
    const std::string at = where + ".pbrMetallicRoughness.baseColorTexture";
    if (base.texCoord < 0) fail(at + ".texCoord", "must be >= 0, got " + std::to_string(base.texCoord));
    desc->base_color_texture = texture_of(base, at);
    if (desc->base_color_texture >= 0) {
      // glTF's base colour is the colour of the metallic lobe too.
      desc->texture_tints_specular = true;
      texcoord = base.texCoord;
    }
    for (const auto& extension : base.extensions) ignored->push_back("baseColorTexture " + extension.first);
  }
  if (m.alphaMode == "MASK") {
    const double factor = m.pbrMetallicRoughness.baseColorFactor[3];
    if (!(factor >= 0 && factor <= 1))
      fail(where + ".pbrMetallicRoughness.baseColorFactor[3]", "must be in [0, 1], got " + str(factor));
    if (!(m.alphaCutoff >= 0) || !std::isfinite(m.alphaCutoff))
      fail(where + ".alphaCutoff", "must be a finite number >= 0, got " + str(m.alphaCutoff));
    desc->alpha_mask = true;
    desc->alpha_texture = desc->base_color_texture;  // glTF's alpha is the base colour's
    desc->alpha_channel = 3;
    desc->alpha_factor = float(factor);
    desc->alpha_cutoff = float(m.alphaCutoff);
  } else if (m.alphaMode != "OPAQUE") {
    ignored->push_back("alphaMode " + m.alphaMode + " (rendered opaque)");
  }
  material_texcoord_[index] = texcoord;
}

std::vector<Float2> GltfLoader::read_texcoords(const tinygltf::Primitive& primitive, int set, const std::string& where,
                                               size_t vertex_count, int material) const {
  const std::string name = "TEXCOORD_" + std::to_string(set);
  auto it = primitive.attributes.find(name);
  if (it == primitive.attributes.end())
    fail(where + ".attributes", "no " + name + ", which materials[" + std::to_string(material) + "]'s texture reads");
  size_t count = 0;
  int components = 0;
  const std::vector<double> values =
      read_accessor(it->second, where + ".attributes." + name, {TINYGLTF_TYPE_VEC2}, true, &count, &components);
  if (count != vertex_count)
    fail(where + ".attributes." + name, std::to_string(count) + " elements for " + std::to_string(vertex_count) + " vertices");
  std::vector<Float2> uvs(count);
  for (size_t v = 0; v < count; ++v) {
    uvs[v] = Float2{float(values[2 * v]), float(values[2 * v + 1])};
    if (!std::isfinite(uvs[v].u) || !std::isfinite(uvs[v].v))
      fail(where + ".attributes." + name, "element " + std::to_string(v) + " is beyond float range");
  }
  return uvs;
}

}  // namespace pm::gltf
