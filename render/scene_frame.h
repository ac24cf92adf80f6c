// A scene at a frame: the camera and lights its tracks (animations/keyframe_track.h) give at
// time frame / frame_rate, plus the facts the renderer needs about a sequence (which frames
// share their lights). Pure host code.
#pragma once

#include <string>
#include <vector>

#include "render/scene.h"

namespace pm {

// Seconds at which frame shows the scene: frame / frame_rate.
double frame_time(const Scene& scene, int frame);

// The camera and the lights at a frame: each track that is present replaces the static value
// (Scene::camera, Scene::lights). A still scene gives its static camera and lights at every frame.
CameraDesc camera_at_frame(const Scene& scene, int frame);
std::vector<LightDesc> lights_at_frame(const Scene& scene, int frame);

// True when both lists have the same lights at bitwise the same positions, powers and (spot
// lights) directions and cone angles (names are not compared): photons traced for one are valid
// for the other.
bool same_lights(const std::vector<LightDesc>& a, const std::vector<LightDesc>& b);

// The first frame of the run of consecutive frames that ends at `frame` and whose lights all
// equal frame's, not going below first_frame: for camera-only motion, the frame whose photons
// the whole run shares (docs/animation.md). frame itself for a still scene and for frames before
// first_frame.
int light_run_start(const Scene& scene, int frame);

// What is wrong with a camera, or "" when it is usable: the view direction is zero, up is zero or
// parallel to it, or the field of view is outside (0, 180) degrees.
std::string camera_problem(const CameraDesc& camera);

}  // namespace pm
