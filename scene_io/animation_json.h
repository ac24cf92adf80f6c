// Owns the "animation" object of a JSON scene file (docs/scene-format.md, "Animation"): frame
// rate, frame range and keyframe tracks of the camera and of named lights, read into
// Scene::animation with positions converted to metres. Every problem is a pm::InputError naming
// the file and the field path.
#pragma once

#include "render/scene.h"
#include "scene_io/json_reader.h"

namespace pm {

// Reads `field` (the scene's "animation" value) into scene->animation. scene->lights and
// scene->camera must already be loaded: light tracks refer to lights by name, and the camera is
// checked at every frame of the range (view direction, up, field of view).
void read_animation_json(const JsonField& field, double meters_per_unit, Scene* scene);

// The largest number of frames a sequence may have (last - first + 1).
constexpr long long kMaxSequenceFrames = 1000000;

// The default last frame of a sequence whose keys end at `last_key_time` seconds: the first frame
// at or after it, ceil(last_key_time * frame_rate) (0 when no key is after time 0).
int default_last_frame(double last_key_time, double frame_rate);

// Fails on `where` (a field) unless the scene's camera is usable at every frame of its range.
void check_animated_camera(const Scene& scene, const JsonField& where);

}  // namespace pm
