// Owns reading a JSON scene's point and spot lights and its camera (docs/scene-format.md), and
// positions in scene units read as metres, which the meshes' vertices (scene_file.cpp) and the
// animation's keys (animation_json.h) share: a position beyond what single-precision geometry
// renders is an InputError naming its field.
#pragma once

#include <vector>

#include "render/scene.h"
#include "scene_io/json_reader.h"

namespace pm {

// `units` (scene units) in metres; fails on `field` where a coordinate lies beyond
// kMaxObjCoordinate metres from the origin.
Float3 position_in_metres(const Float3& units, double meters_per_unit, const JsonField& field);

// The position `field` holds ([x, y, z] in scene units), in metres.
Float3 read_position_in_metres(const JsonField& field, double meters_per_unit);

// The scene's "lights" (none when absent: a scene may be lit by emitting materials alone;
// load_scene_file checks that some light, of either kind, is there).
std::vector<LightDesc> read_lights(const JsonField& root, double meters_per_unit);

// The scene's "camera".
CameraDesc read_camera(const JsonField& root, double meters_per_unit);

}  // namespace pm
