// Owns the built-in default scene: the Cornell box from Cornell University's published measured
// data (geometry in mm, diffuse reflectances reduced to RGB), with the area light replaced by one
// isotropic point light. Embedded in code so the renderer runs with no files at all.
#pragma once

#include "render/scene.h"

namespace pm {

// The Cornell box in metres: 5 walls (2 triangles each) and two closed blocks (top + 4 sides,
// 2 triangles each), 30 triangles. Every triangle's geometric normal (p1 - p0) x (p2 - p0) points
// into the room or out of its block. Name "cornell-box", source "builtin:cornell-box".
Scene builtin_cornell_box();

}  // namespace pm
