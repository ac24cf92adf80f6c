// Reads environments (scene_io/environment_json.h): the JSON scene's "environment" object, and
// maps, which the OpenEXR reader of render/exr_io.h decodes, with the checks that keep a map
// renderable (finite, non-negative texels) before any device is opened.
#include "scene_io/environment_json.h"

#include <cmath>
#include <sstream>
#include <string>

#include "render/errors.h"
#include "render/exr_io.h"
#include "scene_io/load_error.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

const char* const kChannels[3] = {"red", "green", "blue"};

float read_scale(const JsonField& field) {
  const double scale = field.finite_number();
  if (!(scale >= 0) || scale > 1e30) field.fail("must be in [0, 1e30], got " + describe_json_value(field.value()));
  return float(scale);
}

// The map's path as the JSON names it, relative to the scene file's folder.
fs::path map_path(const JsonField& field, const fs::path& scene_dir) {
  const std::string name = field.non_empty_string();
  return fs::path(name).is_absolute() ? fs::path(name) : scene_dir / name;
}

}  // namespace

EnvironmentDesc read_environment_json(const JsonField& field, const fs::path& scene_dir) {
  field.expect_object_with_keys({"radiance", "map", "scale", "rotation_deg"});
  if (field.has("radiance") == field.has("map"))
    field.fail("expected exactly one of \"radiance\" (a constant environment) and \"map\" (an OpenEXR file)");
  EnvironmentDesc env;
  if (field.has("radiance")) {
    for (const char* key : {"scale", "rotation_deg"})
      if (field.has(key)) field.member(key).fail("only a map has this key (\"map\": \"file.exr\")");
    const JsonField radiance = field.member("radiance");
    env.type = EnvironmentType::constant;
    env.radiance = radiance.float3();
    const float values[3] = {env.radiance.x, env.radiance.y, env.radiance.z};
    for (size_t i = 0; i < 3; ++i)
      if (!(values[i] >= 0))
        radiance.element(i).fail("must be >= 0 W sr^-1 m^-2, got " + describe_json_value(radiance.element(i).value()));
    return env;
  }
  if (field.has("rotation_deg")) {
    const JsonField rotation = field.member("rotation_deg");
    const double degrees = rotation.finite_number();
    if (!(std::fabs(degrees) <= 3600))
      rotation.fail("must be in [-3600, 3600] degrees, got " + describe_json_value(rotation.value()));
    env.rotation_degrees = float(degrees);
  }
  const float scale = field.has("scale") ? read_scale(field.member("scale")) : 1.0f;
  const JsonField map = field.member("map");
  return read_environment_map(map_path(map, scene_dir), scale, env.rotation_degrees, map.file() + ": " + map.path());
}

EnvironmentDesc read_environment_map(const fs::path& path, float scale, float rotation_degrees,
                                     const std::string& where) {
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw_input_error(where, "cannot open '" + path.string() + "' (it is a directory)");
  if (!fs::exists(path, ec)) throw_input_error(where, "cannot open '" + path.string() + "' (no such file)");
  FrameImage image;
  try {
    image = read_exr(path.string());
  } catch (const InputError& e) {
    throw_input_error(where, e.what());
  }
  // The combined layer (bare R, G, B) when the file has one, else its first RGB layer.
  const ImageLayer* layer = image.find("");
  if (!layer) layer = &image.layers.front();
  const size_t texels = size_t(image.width) * size_t(image.height);
  for (size_t t = 0; t < texels; ++t) {
    for (int c = 0; c < 3; ++c) {
      const float v = layer->rgb[3 * t + size_t(c)];
      if (std::isfinite(v) && v >= 0) continue;
      std::ostringstream text;
      text << "'" << path.string() << "': texel (" << t % size_t(image.width) << ", " << t / size_t(image.width) << ") "
           << kChannels[c] << " is " << v << "; an environment's radiance must be finite and >= 0";
      throw_input_error(where, text.str());
    }
  }
  EnvironmentDesc env;
  env.type = EnvironmentType::map;
  env.map_file = path.string();
  env.width = image.width;
  env.height = image.height;
  env.scale = scale;
  env.rotation_degrees = rotation_degrees;
  env.texels = layer->rgb;
  for (float& v : env.texels) v *= scale;
  return env;
}

}  // namespace pm
