// Owns reading a JSON scene's "environment" object (docs/scene-format.md) into
// pm::EnvironmentDesc: a constant radiance, or an equirectangular OpenEXR map with its scale and
// turn about +y, the map's path relative to the scene file. Every problem is one InputError
// naming the scene file, the field and, for the map, the EXR file.
#pragma once

#include <filesystem>

#include "render/scene.h"
#include "scene_io/json_reader.h"

namespace pm {

EnvironmentDesc read_environment_json(const JsonField& field, const std::filesystem::path& scene_dir);

}  // namespace pm
