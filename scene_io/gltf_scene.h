// Owns loading glTF 2.0 scenes (.gltf with embedded or external buffers, .glb) into pm::Scene
// through tinygltf: triangle meshes with their node transforms, metallic-roughness materials
// mapped onto modified Phong, the first (or the named) perspective camera, KHR_lights_punctual
// point lights converted from candela to watts, and node animations of the camera and the
// lights sampled into keyframe tracks. docs/scene-format.md, "glTF scenes", has the mappings.
// Every problem is a pm::InputError "<file>: <where>: <what>" on one line.
#pragma once

#include <string>

#include "render/scene.h"
#include "scene_io/scene_file.h"

namespace pm {

// Frame rate of a glTF sequence when the file does not set one (extras.pmrender.frame_rate).
constexpr double kGltfDefaultFrameRate = 24.0;

// Luminous efficacy of light at 555 nm: each RGB channel of a glTF light or emissive material is
// taken as light of that wavelength.
constexpr double kLumensPerWatt = 683.0;

// Watts of one RGB channel of a point light of `candela` (lm/sr) and colour component `colour`:
// an isotropic source of I cd emits 4 pi I lm; each channel is taken as light at 555 nm, where
// 683 lm make one watt. A spot light's power is converted alike (LightDesc: the power of the
// point light with the same on-axis intensity).
double candela_to_watts(double candela, double colour);

// Phong exponent of the glossy lobe for a glTF roughness r: with alpha = r^2 (the GGX/Beckmann
// width), n = 2 / alpha^2 - 2 (Walter et al. 2007). Infinite at r = 0.
double roughness_to_phong_exponent(double roughness);
// Exponents at or above this become a perfect mirror instead of a glossy lobe.
constexpr double kGltfMirrorExponent = 10000.0;

// environment: as for load_scene_file (glTF has none of its own).
Scene load_gltf_scene(const std::string& path, SceneLoadReport* report = nullptr,
                      const EnvironmentDesc* environment = nullptr);

}  // namespace pm
