// Owns OBJ mesh loading through tinyobjloader: text validation first, then parsing with
// triangulation, recovery of usemtl names per triangle, MTL collection and degenerate removal.
#include "scene_io/obj_mesh.h"

#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>

#include "scene_io/load_error.h"

namespace pm {
namespace {

// tinyobjloader only keeps a usemtl name if some mtllib defined it; faces under any other name
// get material id -1, indistinguishable from faces with no usemtl. We need the name (it may refer
// to a JSON material), so the text handed to tinyobjloader starts with an extra line
// "mtllib <this sentinel>", for which our reader registers every usemtl slot token of the file
// (check_obj_text rewrote the usemtl lines to those tokens). The material id of a face is then
// its index in ObjTextFacts::usemtl_names.
const char kUsemtlNamesSentinel[] = "<pmrender:usemtl-names>";

MtlTexture mtl_texture(const std::string& file, const tinyobj::texture_option_t& options) {
  MtlTexture texture;
  texture.file = file;
  texture.clamp = options.clamp;
  texture.channel = options.imfchan;
  return texture;
}

// The texture statements of a material that pmrender does not render, for the loader's warning.
std::vector<std::string> ignored_mtl_statements(const tinyobj::material_t& m) {
  std::vector<std::string> ignored;
  const std::pair<const std::string*, const char*> maps[] = {
      {&m.ambient_texname, "map_Ka"},   {&m.specular_texname, "map_Ks"},  {&m.specular_highlight_texname, "map_Ns"},
      {&m.bump_texname, "map_bump"},    {&m.displacement_texname, "disp"}, {&m.reflection_texname, "refl"},
      {&m.roughness_texname, "map_Pr"}, {&m.metallic_texname, "map_Pm"},  {&m.sheen_texname, "map_Ps"},
      {&m.emissive_texname, "map_Ke"},  {&m.normal_texname, "norm"}};
  for (const auto& map : maps)
    if (!map.first->empty()) ignored.push_back(map.second);
  // Offsets and scales of the texture coordinates are not applied: the image is used as it is.
  auto transformed = [](const tinyobj::texture_option_t& o) {
    return o.origin_offset[0] != 0 || o.origin_offset[1] != 0 || o.scale[0] != 1 || o.scale[1] != 1;
  };
  if (!m.diffuse_texname.empty() && transformed(m.diffuse_texopt)) ignored.push_back("map_Kd -o/-s");
  if (!m.alpha_texname.empty() && transformed(m.alpha_texopt)) ignored.push_back("map_d -o/-s");
  return ignored;
}

class SceneMtlReader : public tinyobj::MaterialReader {
 public:
  SceneMtlReader(std::string obj_dir, const std::vector<ObjUsemtl>* usemtl_names, bool read_files,
                 std::map<std::string, MtlMaterial>* found)
      : obj_dir_(std::move(obj_dir)), usemtl_names_(usemtl_names), read_files_(read_files), found_(found) {}

  bool operator()(const std::string& mat_id, std::vector<tinyobj::material_t>* materials,
                  std::map<std::string, int>* mat_map, std::string*, std::string*) override {
    if (mat_id == kUsemtlNamesSentinel) {
      for (size_t slot = 0; slot < usemtl_names_->size(); ++slot) {
        tinyobj::material_t placeholder = tinyobj::material_t();
        placeholder.name = usemtl_slot_token(slot);
        mat_map->insert({placeholder.name, static_cast<int>(materials->size())});
        materials->push_back(placeholder);
      }
      return true;
    }
    if (!read_files_) return true;
    const std::string path = resolve_mtl_file(obj_dir_, mat_id);
    if (path.empty()) return false;  // tinyobjloader tries the line's next name
    std::ifstream file(path, std::ios::binary);
    std::stringstream in;
    in << file.rdbuf();
    if (in.str().compare(0, 3, "\xEF\xBB\xBF") == 0) in.str(in.str().substr(3));  // a byte order mark
    std::map<std::string, int> file_map;
    std::vector<tinyobj::material_t> file_materials;
    std::string warn, err;
    tinyobj::LoadMtl(&file_map, &file_materials, &in, &warn, &err);
    for (const tinyobj::material_t& m : file_materials) {
      if (found_->count(m.name)) continue;
      MtlMaterial mtl;
      mtl.name = m.name;
      mtl.mtl_file = path;
      for (int c = 0; c < 3; ++c) {
        mtl.kd[c] = m.diffuse[c];
        mtl.ks[c] = m.specular[c];
        mtl.ke[c] = m.emission[c];
      }
      mtl.ns = m.shininess;
      mtl.illum = m.illum;
      if (!m.diffuse_texname.empty()) mtl.map_kd = mtl_texture(m.diffuse_texname, m.diffuse_texopt);
      if (!m.alpha_texname.empty()) mtl.map_d = mtl_texture(m.alpha_texname, m.alpha_texopt);
      mtl.ignored = ignored_mtl_statements(m);
      (*found_)[m.name] = mtl;
    }
    return true;
  }

 private:
  std::string obj_dir_;
  const std::vector<ObjUsemtl>* usemtl_names_;
  bool read_files_;
  std::map<std::string, MtlMaterial>* found_;
};

// tinyobjloader's own errors (those our text check does not pre-empt) name a line of the text we
// gave it, one below the file's because of the sentinel line; report the file's line instead.
std::string tinyobj_error_in_file_terms(const std::string& obj_path, const std::string& err) {
  std::string first = err.substr(0, err.find('\n'));
  // Its messages end like "... line 5.)" or "(line 5.)"; that part is replaced by our prefix.
  static const std::regex line_pattern("[ (]*line:? ?([0-9]+)[.)]*");
  std::smatch match;
  if (std::regex_search(first, match, line_pattern)) {
    const long line = std::stol(match[1].str()) - 1;
    const std::string text = first.substr(0, static_cast<size_t>(match.position(0))) + match.suffix().str();
    return file_line(obj_path, static_cast<size_t>(line > 0 ? line : 1)) + ": " + text;
  }
  return obj_path + ": " + (first.empty() ? std::string("tinyobjloader failed") : first);
}

double length_squared(double x, double y, double z) { return x * x + y * y + z * z; }

}  // namespace

bool is_degenerate_triangle(const Float3& a, const Float3& b, const Float3& c) {
  const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  const double e3[3] = {double(c.x) - b.x, double(c.y) - b.y, double(c.z) - b.z};
  const double cross[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2],
                           e1[0] * e2[1] - e1[1] * e2[0]};
  const double twice_area = std::sqrt(length_squared(cross[0], cross[1], cross[2]));
  const double longest_squared =
      std::max({length_squared(e1[0], e1[1], e1[2]), length_squared(e2[0], e2[1], e2[2]),
                length_squared(e3[0], e3[1], e3[2])});
  // twice_area / longest is the height over the longest edge; compared relative to that edge
  // because float vertices carry ~6e-8 relative rounding, so anything flatter has no usable normal.
  return !(twice_area > 1e-7 * longest_squared);
}

ObjMesh load_obj_mesh(const std::string& path, bool read_mtl_files) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_input_error(path, std::string("cannot open (") + std::strerror(errno) + ")");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  const std::string obj_dir = std::filesystem::path(path).parent_path().string();

  const ObjTextFacts facts = check_obj_text(path, obj_dir, text, read_mtl_files);

  ObjMesh mesh;
  mesh.usemtl_names = facts.usemtl_names;
  mesh.warnings = facts.warnings;
  SceneMtlReader reader(obj_dir, &facts.usemtl_names, read_mtl_files, &mesh.mtl_materials);
  std::istringstream stream(std::string("mtllib ") + kUsemtlNamesSentinel + "\n" + facts.text_for_tinyobj);
  tinyobj::attrib_t attrib;
  std::vector<tinyobj::shape_t> shapes;
  std::vector<tinyobj::material_t> placeholders;
  std::string warn, err;
  const bool ok = tinyobj::LoadObj(&attrib, &shapes, &placeholders, &warn, &err, &stream, &reader,
                                   /*triangulate=*/true);
  if (!ok || !err.empty()) throw_input_error("", tinyobj_error_in_file_terms(path, err));

  const size_t vertex_count = attrib.vertices.size() / 3;
  const size_t texcoord_count = attrib.texcoords.size() / 2;
  // vt's v grows upwards from the image's bottom row; the scene's (glTF's) from its top row.
  auto texcoord = [&](int index) {
    if (index < 0 || size_t(index) >= texcoord_count) return Float2{0, 0};  // none, or the tolerated out-of-range index
    return Float2{attrib.texcoords[2 * size_t(index)], 1.0f - attrib.texcoords[2 * size_t(index) + 1]};
  };
  mesh.positions.resize(vertex_count);
  for (size_t i = 0; i < vertex_count; ++i) {
    mesh.positions[i] =
        Float3{attrib.vertices[3 * i], attrib.vertices[3 * i + 1], attrib.vertices[3 * i + 2]};
  }

  for (const tinyobj::shape_t& shape : shapes) {
    const tinyobj::mesh_t& m = shape.mesh;
    size_t corner = 0;
    for (size_t face = 0; face < m.num_face_vertices.size(); ++face) {
      const size_t corners = m.num_face_vertices[face];
      // Triangulation is on, so every face has 3 corners; anything else is skipped defensively.
      if (corners != 3) {
        corner += corners;
        continue;
      }
      uint32_t v[3];
      for (int k = 0; k < 3; ++k) {
        const int index = m.indices[corner + k].vertex_index;
        if (index < 0 || static_cast<size_t>(index) >= vertex_count) {
          throw_input_error(path, "face vertex index " + std::to_string(index + 1) + " out of range (" +
                                      std::to_string(vertex_count) + " vertices)");
        }
        v[k] = static_cast<uint32_t>(index);
      }
      corner += 3;
      if (is_degenerate_triangle(mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]])) {
        ++mesh.degenerate_triangles_dropped;
        continue;
      }
      mesh.indices.insert(mesh.indices.end(), v, v + 3);
      for (int k = 0; k < 3; ++k) mesh.triangle_uvs.push_back(texcoord(m.indices[corner - 3 + k].texcoord_index));
      const int material = face < m.material_ids.size() ? m.material_ids[face] : -1;
      mesh.triangle_usemtl.push_back(
          material >= 0 && static_cast<size_t>(material) < facts.usemtl_names.size() ? material : -1);
    }
  }
  // Large convex faces, fanned out by the text check instead of tinyobjloader.
  for (const ObjFanTriangle& t : facts.fan_triangles) {
    const uint32_t* v = t.vertices;
    if (is_degenerate_triangle(mesh.positions[v[0]], mesh.positions[v[1]], mesh.positions[v[2]])) {
      ++mesh.degenerate_triangles_dropped;
      continue;
    }
    mesh.indices.insert(mesh.indices.end(), v, v + 3);
    for (int k = 0; k < 3; ++k) mesh.triangle_uvs.push_back(texcoord(t.texcoords[k]));
    mesh.triangle_usemtl.push_back(t.usemtl);
  }
  return mesh;
}

}  // namespace pm
