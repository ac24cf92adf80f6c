// Owns the line-by-line validation of OBJ text that runs before tinyobjloader parses it.
// tinyobjloader 2.0rc10 (Debian 12) accepts some broken input silently — "v nan 0 0" becomes 0,
// out-of-range positive face indices pass through, and its out-of-range warning carries the last
// line number rather than the face's — so this pass rejects such lines itself, with the real line.
// It also collects the usemtl names and prepares the text tinyobjloader is given (see below).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace pm {

struct ObjUsemtl {
  std::string name;
  size_t first_line = 0;  // 1-based line of its first usemtl statement
};

// A triangle of a large convex face, fanned out by check_obj_text itself (see below).
struct ObjFanTriangle {
  uint32_t vertices[3];   // 0-based vertex indices
  int32_t usemtl;         // index into usemtl_names; -1 before any usemtl
  int32_t texcoords[3];   // 0-based texture coordinate indices; -1: none or out of range
};

// Faces of more corners than this are not left to tinyobjloader, whose ear clipping takes time
// quadratic in the corners (100,000 corners: 22 s): convex ones are fanned out here in linear
// time; non-convex ones of up to kMaxEarClippedCorners still go to tinyobjloader, larger ones are
// refused.
constexpr size_t kLargeFaceCorners = 64;
constexpr size_t kMaxEarClippedCorners = 2048;

// Vertex coordinates must be at most this large in magnitude (file units): beyond it the single-
// precision ray-triangle products (squares of edge lengths) overflow and surfaces vanish.
constexpr double kMaxObjCoordinate = 1e15;

struct ObjTextFacts {
  std::vector<ObjUsemtl> usemtl_names;  // distinct names, in order of first use
  // The text to hand tinyobjloader: the same lines, "\n"-terminated, with every usemtl statement
  // rewritten to "usemtl <usemtl_slot_token(i)>" (i indexing usemtl_names). Names may contain
  // blanks, which tinyobjloader's usemtl parsing would cut off; tokens cannot.
  std::string text_for_tinyobj;
  // The triangles of large convex faces; their lines are blanked in text_for_tinyobj.
  std::vector<ObjFanTriangle> fan_triangles;
  // Tolerated problems, one line each: out-of-range texture coordinate or normal indices (such a
  // corner's texture coordinates read as (0, 0)).
  std::vector<std::string> warnings;
};

// The blank-free stand-in for usemtl_names[slot] in ObjTextFacts::text_for_tinyobj.
std::string usemtl_slot_token(size_t slot);

// Splits text into lines the way tinyobjloader does ("\n", "\r\n" and a lone "\r" all end a line),
// so line numbers agree with its own messages.
std::vector<std::string> split_obj_lines(const std::string& text);

// A UTF-8 byte order mark at the start of text is skipped (it would hide the first statement).
// Throws InputError "<obj_path>: line N: <problem>" for:
//   vertices without 3 decimal, finite coordinates of magnitude at most kMaxObjCoordinate;
//   texture coordinates (vt) without 1 to 3 decimal, finite values;
//   non-convex faces of more than kMaxEarClippedCorners corners;
//   face/line/point elements with a malformed or zero index, an out-of-range vertex index, or
//   (faces) fewer than 3 corners; usemtl without a name; and, when check_mtllib is set, an mtllib line
//   none of whose files can be opened (relative to obj_dir).
// Out-of-range texture coordinate and normal indices only add a warning (converted scenes in the
// wild have one vt too few): such corners get texture coordinates (0, 0); normals are unused.
ObjTextFacts check_obj_text(const std::string& obj_path, const std::string& obj_dir, const std::string& text,
                            bool check_mtllib);

// Resolves an mtllib file name the way the mesh loader opens it: relative to the OBJ's folder
// unless absolute. Returns "" when it is not a readable regular file.
std::string resolve_mtl_file(const std::string& obj_dir, const std::string& name);

// tinyobjloader's split of an mtllib line: on spaces, with "\ " escaping a space.
std::vector<std::string> split_mtllib_names(const std::string& rest_of_line);

}  // namespace pm
