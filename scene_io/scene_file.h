// Owns the public entry point for scene files: load_scene_file reads a pmrender JSON scene
// (format "pmrender-scene", version 1; docs/scene-format.md) and the OBJ/MTL files it names, and
// returns a pm::Scene in metres. Every problem is a pm::InputError with a one-line message that
// names the file and the field path or line.
#pragma once

#include <string>
#include <vector>

#include "render/scene.h"

namespace pm {

// The scene format version this build reads.
constexpr int kSceneFormatVersion = 1;

// What loading tolerated without failing, for the caller to print or ignore.
struct SceneLoadReport {
  size_t degenerate_triangles_dropped = 0;  // zero-area triangles removed, over all meshes
  // One line each, e.g. "room.obj: 2 degenerate triangles dropped" or
  // "room.mtl: material 'gold': reflectance sum above 1 (red 1.2) scaled down to 0.99".
  std::vector<std::string> warnings;
};

// Loads the scene at path. Positions (meshes, lights, camera) are converted to metres with the
// file's meters_per_unit. Scene.name is the "name" key or else the file stem; Scene.source = path.
// Scene.materials holds the materials the triangles use, in order of first use. When report is
// given it is reset and then filled with what this load tolerated. When environment is given it
// becomes the scene's environment, replacing the file's (the command line's --environment), before
// the check that the scene has some light.
Scene load_scene_file(const std::string& path, SceneLoadReport* report = nullptr,
                      const EnvironmentDesc* environment = nullptr);

}  // namespace pm
