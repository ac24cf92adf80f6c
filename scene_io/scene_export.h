// Owns writing a loaded scene back out as a pmrender scene file (docs/scene-format.md): one JSON
// file and one OBJ per material, every position in metres, every mesh with its material named
// explicitly. What the renderer sees, in the plainest form another program can read: the
// independent renderer of the tests (tests/mitsuba/) converts this, not the original files, so
// both renderers get the same triangles, materials, lights and camera, the built-in Cornell box
// included.
#pragma once

#include <string>

#include "render/scene.h"

namespace pm {

// Writes json_path and, beside it, "<stem>.<k>.obj" for the k-th material in use. Camera and
// lights are those of `frame` (a still scene: its only ones). Files go through AtomicFile;
// errors are std::runtime_error naming the file.
void export_scene(const Scene& scene, int frame, const std::string& json_path);

}  // namespace pm
