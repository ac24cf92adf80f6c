// Owns reading an environment (docs/scene-format.md) into pm::EnvironmentDesc: a JSON scene's
// "environment" object (a constant radiance, or an equirectangular OpenEXR map with its scale and
// turn about +y, the map's path relative to the scene file), and the map reading that the
// command line's --environment shares. Every problem is one InputError naming where it was asked
// for (the scene file and field, or the option) and, for a map, the EXR file.
#pragma once

#include <filesystem>
#include <string>

#include "render/scene.h"
#include "scene_io/json_reader.h"

namespace pm {

EnvironmentDesc read_environment_json(const JsonField& field, const std::filesystem::path& scene_dir);

// The map at `path` as an environment, its texels times `scale`, turned by rotation_degrees about
// +y. A missing, unreadable, negative or non-finite map is an InputError "<where>: ...".
EnvironmentDesc read_environment_map(const std::filesystem::path& path, float scale, float rotation_degrees,
                                     const std::string& where);

}  // namespace pm
