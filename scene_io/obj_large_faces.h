// Owns the linear-time triangulation of large convex OBJ faces (obj_text_check.h says why
// tinyobjloader does not get them): a convexity test in the face's own plane, then a fan.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "scene_io/obj_text_check.h"

namespace pm {

// True when the polygon (0-based indices into positions, in order) is convex: in the plane of its
// Newell normal every corner turns the same way (collinear corners allowed) and the boundary
// winds around once (a pentagram turns the same way at every corner but winds twice). A polygon
// without area counts as convex: its fan has only degenerate triangles, which the loader drops.
bool is_convex_polygon(const std::vector<std::array<double, 3>>& positions, const std::vector<uint32_t>& corners);

// Appends the fan (c0, ci, ci+1) of the polygon to out, each triangle with the given usemtl slot
// and its corners' texture coordinate indices (texcoords: one per corner, -1 for none).
void append_fan(const std::vector<uint32_t>& corners, const std::vector<int32_t>& texcoords, int32_t usemtl,
                std::vector<ObjFanTriangle>* out);

}  // namespace pm
