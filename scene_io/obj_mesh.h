// Owns reading one Wavefront OBJ mesh (and the MTL files it names) into triangles with per-
// triangle usemtl names, in the file's own units. Which material a usemtl name finally means
// (scene JSON first, then MTL) is decided by the scene loader, not here.
#pragma once

#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include "render/scene.h"
#include "scene_io/mtl_material.h"
#include "scene_io/obj_text_check.h"

namespace pm {

struct ObjMesh {
  std::vector<Float3> positions;                     // as written in the file (scene units)
  std::vector<uint32_t> indices;                     // three per triangle, into positions
  std::vector<Float2> triangle_uvs;                  // three per triangle (vt, v flipped: 0 = top); (0, 0) without
  std::vector<int32_t> triangle_usemtl;              // index into usemtl_names; -1 before any usemtl
  std::vector<ObjUsemtl> usemtl_names;               // distinct usemtl names with their first line
  std::map<std::string, MtlMaterial> mtl_materials;  // by name; first definition wins
  size_t degenerate_triangles_dropped = 0;
  std::vector<std::string> warnings;  // one line each, naming the file

  size_t triangle_count() const { return indices.size() / 3; }
};

// Reads, validates (see check_obj_text) and triangulates the OBJ at path. Degenerate triangles
// (zero area to float precision: height under 1e-7 of the longest edge) are dropped and counted.
// With read_mtl_files false, mtllib lines are ignored (the caller overrides every material).
// Throws InputError "<path>: line N: ..." or "<path>: ...".
ObjMesh load_obj_mesh(const std::string& path, bool read_mtl_files);

// True when the triangle's area is zero to float precision (see load_obj_mesh).
bool is_degenerate_triangle(const Float3& a, const Float3& b, const Float3& c);

}  // namespace pm
