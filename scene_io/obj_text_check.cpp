// Owns the pre-parse validation of OBJ text (see obj_text_check.h for why it exists): vertex
// coordinates, element indices, usemtl names and mtllib files, each error with its line number.
#include "scene_io/obj_text_check.h"

#include <array>
#include <cerrno>
#include <cfloat>
#include <climits>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <string_view>
#include <unordered_map>
#include <utility>

#include "scene_io/load_error.h"
#include "scene_io/obj_large_faces.h"

namespace pm {
namespace {

enum class ObjStatement { kOther, kVertex, kTexcoord, kNormal, kFace, kLine, kPoint, kUsemtl, kMtllib };

bool is_blank(char c) { return c == ' ' || c == '\t'; }

// A statement's place for its messages, "<file>: line N", made only when a message needs it: the
// check runs over every line of scenes of a million lines.
struct LinePlace {
  const std::string& file;
  size_t line;
  std::string text() const { return file_line(file, line); }
};

// Classifies a line (leading blanks already skipped) with the same tests tinyobjloader uses, so
// both passes agree on what each line is. *rest is set to the text after the keyword.
ObjStatement classify(std::string_view line, size_t start, size_t* rest) {
  auto keyword_then_blank = [&](std::string_view keyword) {
    const size_t n = keyword.size();
    if (line.compare(start, n, keyword) != 0) return false;
    if (start + n >= line.size() || !is_blank(line[start + n])) return false;
    *rest = start + n;
    return true;
  };
  if (keyword_then_blank("v")) return ObjStatement::kVertex;
  if (keyword_then_blank("vt")) return ObjStatement::kTexcoord;
  if (keyword_then_blank("vn")) return ObjStatement::kNormal;
  if (keyword_then_blank("f")) return ObjStatement::kFace;
  if (keyword_then_blank("l")) return ObjStatement::kLine;
  if (keyword_then_blank("p")) return ObjStatement::kPoint;
  if (line.compare(start, 6, "usemtl") == 0) {  // tinyobjloader needs no blank after usemtl
    *rest = start + 6;
    return ObjStatement::kUsemtl;
  }
  if (keyword_then_blank("mtllib")) return ObjStatement::kMtllib;
  return ObjStatement::kOther;
}

// The blank-separated tokens of line from `from`, into *tokens (cleared first; views of line).
void split_blanks(std::string_view line, size_t from, std::vector<std::string_view>* tokens) {
  tokens->clear();
  size_t i = from;
  while (i < line.size()) {
    while (i < line.size() && is_blank(line[i])) ++i;
    const size_t begin = i;
    while (i < line.size() && !is_blank(line[i])) ++i;
    if (i > begin) tokens->push_back(line.substr(begin, i - begin));
  }
}

// The C library's number parsers read NUL-terminated text: a token's copy, on the stack when short.
template <typename Parse>
auto parse_terminated(std::string_view token, Parse parse) {
  char small[64];
  std::string large;
  const char* text = small;
  if (token.size() < sizeof(small)) {
    std::memcpy(small, token.data(), token.size());
    small[token.size()] = '\0';
  } else {
    large.assign(token);
    text = large.c_str();
  }
  char* end = nullptr;
  const auto value = parse(text, &end);
  return std::make_pair(value, end == text + token.size());
}

// Only what tinyobjloader's own number parser understands (no hex, inf or nan spellings), so a
// value that passes here is the value it will read.
bool parse_decimal(std::string_view token, double* value) {
  if (token.empty() || token.find_first_not_of("0123456789+-.eE") != std::string_view::npos) return false;
  const auto [parsed, whole] = parse_terminated(token, [](const char* text, char** end) { return std::strtod(text, end); });
  *value = parsed;
  return whole;
}

bool parse_index(std::string_view text, long* value) {
  if (text.empty()) return false;
  errno = 0;
  const auto [parsed, whole] =
      parse_terminated(text, [](const char* digits, char** end) { return std::strtol(digits, end, 10); });
  *value = parsed;
  return errno == 0 && whole && *value >= INT_MIN && *value <= INT_MAX;
}

struct AttributeCounts {
  size_t vertices = 0, texcoords = 0, normals = 0;
};

enum class IndexProblem { kNone, kInvalid, kOutOfRange };

// Checks one index of one kind and describes any problem in *message: positive indices may refer
// to any vertex in the file (like tinyobjloader, which resolves them after reading everything),
// negative ones count back from the vertices defined so far.
IndexProblem check_index(const char* element, const char* kind, std::string_view text, size_t total, size_t so_far,
                         std::string* message) {
  long index = 0;
  IndexProblem problem = IndexProblem::kNone;
  if (!parse_index(text, &index) || index == 0)
    problem = IndexProblem::kInvalid;
  else if ((index > 0 && static_cast<size_t>(index) > total) || (index < 0 && static_cast<size_t>(-index) > so_far))
    problem = IndexProblem::kOutOfRange;
  if (problem == IndexProblem::kNone) return problem;
  // "face index 99", "face texture coordinate index 5": vertex indices are the default kind.
  const bool vertex = std::strcmp(kind, "vertex") == 0;
  const std::string what = vertex ? std::string(element) + " index" : std::string(element) + " " + kind + " index";
  const std::string plural = vertex ? "vertices" : std::string(kind) + "s";
  if (!parse_index(text, &index))
    *message = what + " '" + std::string(text) + "' is not an integer";
  else if (index == 0)
    *message = what + " 0 is invalid (OBJ indices start at 1)";
  else if (index > 0)
    *message = what + " " + std::to_string(index) + " out of range (" + std::to_string(total) + " " + plural + ")";
  else
    *message = what + " " + std::to_string(index) + " out of range (" + std::to_string(so_far) + " " + plural +
               " before this line)";
  return problem;
}

// Out-of-range texture coordinate and normal indices, tolerated because some converted scenes
// have one vt too few: such a corner's texture coordinates read as (0, 0); normals are unused.
struct UnusedAttributeIssues {
  size_t count = 0;
  std::string first;  // "<file>: line N: <problem>"
};

// One corner "v", "v/vt", "v//vn" or "v/vt/vn".
void check_corner(const LinePlace& where, const char* element, std::string_view corner, const AttributeCounts& total,
                  const AttributeCounts& so_far, UnusedAttributeIssues* unused) {
  std::string_view parts[3];
  size_t count = 0, begin = 0;
  for (;;) {
    const size_t slash = corner.find('/', begin);
    const std::string_view part = corner.substr(begin, slash == std::string_view::npos ? std::string_view::npos : slash - begin);
    if (count < 3) parts[count] = part;
    ++count;
    if (slash == std::string_view::npos) break;
    begin = slash + 1;
  }
  const bool well_formed = count <= 3 && !parts[0].empty() && (count < 2 || !parts[1].empty() || count == 3) &&
                           (count < 3 || !parts[2].empty());
  if (!well_formed) {
    throw_input_error(where.text(), std::string(element) + " corner '" + std::string(corner) +
                                        "' is not of the form v, v/vt, v//vn or v/vt/vn");
  }
  std::string message;
  if (check_index(element, "vertex", parts[0], total.vertices, so_far.vertices, &message) != IndexProblem::kNone)
    throw_input_error(where.text(), message);
  auto check_unused = [&](const char* kind, std::string_view text, size_t kind_total, size_t kind_so_far) {
    const IndexProblem problem = check_index(element, kind, text, kind_total, kind_so_far, &message);
    if (problem == IndexProblem::kInvalid) throw_input_error(where.text(), message);  // tinyobjloader fails on these
    if (problem == IndexProblem::kOutOfRange && unused->count++ == 0) unused->first = where.text() + ": " + message;
  };
  if (count >= 2 && !parts[1].empty()) check_unused("texture coordinate", parts[1], total.texcoords, so_far.texcoords);
  if (count == 3) check_unused("normal", parts[2], total.normals, so_far.normals);
}

std::array<double, 3> check_vertex(const LinePlace& where, const std::vector<std::string_view>& coordinates) {
  if (coordinates.size() < 3) {
    throw_input_error(where.text(), "vertex has " + std::to_string(coordinates.size()) + " coordinates (need x y z)");
  }
  std::array<double, 3> position{};
  for (size_t i = 0; i < 3; ++i) {
    double& value = position[i];
    const std::string_view text = coordinates[i];
    if (!parse_decimal(text, &value)) {
      throw_input_error(where.text(), "vertex coordinate '" + std::string(text) + "' is not a finite decimal number");
    }
    if (!std::isfinite(value) || std::fabs(value) > FLT_MAX) {
      throw_input_error(where.text(), "vertex coordinate '" + std::string(text) + "' is not a finite float");
    }
    if (std::fabs(value) > kMaxObjCoordinate) {
      throw_input_error(where.text(), "vertex coordinate '" + std::string(text) +
                                          "' is too large to render (single-precision geometry needs |x| <= 1e15)");
    }
  }
  return position;
}

// The 0-based vertex of a corner that check_corner accepted ("-1/2/3" -> so_far - 1).
uint32_t corner_vertex(std::string_view corner, size_t so_far) {
  long index = 0;
  parse_index(corner.substr(0, corner.find('/')), &index);
  return uint32_t(index > 0 ? index - 1 : long(so_far) + index);
}

// The 0-based texture coordinate of a corner that check_corner accepted, -1 when it has none or
// its index is out of range (the tolerated problem).
int32_t corner_texcoord(std::string_view corner, size_t total, size_t so_far) {
  const size_t slash = corner.find('/');
  if (slash == std::string_view::npos || slash + 1 >= corner.size() || corner[slash + 1] == '/') return -1;
  long index = 0;
  const std::string_view rest = corner.substr(slash + 1);
  parse_index(rest.substr(0, rest.find('/')), &index);
  if (index > 0 && size_t(index) <= total) return int32_t(index - 1);
  if (index < 0 && size_t(-index) <= so_far) return int32_t(long(so_far) + index);
  return -1;
}

// vt u [v [w]]: one to three finite decimals (tinyobjloader reads "nan" as a number).
void check_texcoord(const LinePlace& where, const std::vector<std::string_view>& values) {
  if (values.empty() || values.size() > 3)
    throw_input_error(where.text(), "texture coordinate has " + std::to_string(values.size()) +
                                        " values (need u, v and an optional w)");
  for (const std::string_view token : values) {
    double value = 0;
    if (!parse_decimal(token, &value) || !std::isfinite(value) || std::fabs(value) > FLT_MAX)
      throw_input_error(where.text(), "texture coordinate '" + std::string(token) + "' is not a finite decimal number");
  }
}

// Calls line(text of the line, its number from 1) for each line of text, split as
// split_obj_lines splits it.
template <typename PerLine>
void for_each_obj_line(std::string_view text, PerLine line) {
  size_t begin = 0, number = 0;
  for (size_t i = 0; i < text.size(); ++i) {
    if (text[i] != '\n' && text[i] != '\r') continue;
    line(text.substr(begin, i - begin), ++number);
    if (text[i] == '\r' && i + 1 < text.size() && text[i + 1] == '\n') ++i;
    begin = i + 1;
  }
  if (begin < text.size()) line(text.substr(begin), ++number);
}

// A face of more than kLargeFaceCorners corners, decided on once every vertex is known.
struct LargeFace {
  size_t line = 0;
  size_t text_offset = 0, text_length = 0;  // its line in text_for_tinyobj, without the '\n'
  int32_t usemtl = -1;
  std::vector<uint32_t> corners;
  std::vector<int32_t> texcoords;
};

}  // namespace

std::string usemtl_slot_token(size_t slot) { return "pmrender-usemtl-" + std::to_string(slot); }

std::vector<std::string> split_obj_lines(const std::string& text) {
  std::vector<std::string> lines;
  for_each_obj_line(text, [&](std::string_view line, size_t) { lines.emplace_back(line); });
  return lines;
}

std::vector<std::string> split_mtllib_names(const std::string& rest_of_line) {
  std::vector<std::string> names;
  std::string name;
  bool escaping = false;
  for (char c : rest_of_line) {
    if (!escaping && c == '\\') {
      escaping = true;
      continue;
    }
    if (!escaping && c == ' ') {
      if (!name.empty()) names.push_back(name);
      name.clear();
      continue;
    }
    escaping = false;
    name += c;
  }
  if (!name.empty()) names.push_back(name);
  return names;
}

std::string resolve_mtl_file(const std::string& obj_dir, const std::string& name) {
  namespace fs = std::filesystem;
  fs::path path = fs::path(name).is_absolute() ? fs::path(name) : fs::path(obj_dir) / name;
  std::error_code ec;
  if (!fs::is_regular_file(path, ec)) return "";
  std::ifstream probe(path);
  return probe ? path.string() : "";
}

ObjTextFacts check_obj_text(const std::string& obj_path, const std::string& obj_dir, const std::string& file_text,
                            bool check_mtllib) {
  // A byte order mark would make the first line unrecognisable to both passes.
  const bool bom = file_text.compare(0, 3, "\xEF\xBB\xBF") == 0;
  const std::string_view text = std::string_view(file_text).substr(bom ? 3 : 0);

  // Pass 1: totals, because positive indices may point at vertices defined further down.
  AttributeCounts total;
  for_each_obj_line(text, [&](std::string_view line, size_t) {
    const size_t start = line.find_first_not_of(" \t");
    if (start == std::string_view::npos) return;
    size_t rest = 0;
    switch (classify(line, start, &rest)) {
      case ObjStatement::kVertex:
        ++total.vertices;
        break;
      case ObjStatement::kTexcoord:
        ++total.texcoords;
        break;
      case ObjStatement::kNormal:
        ++total.normals;
        break;
      default:
        break;
    }
  });

  // Pass 2: validate each statement with its line number.
  ObjTextFacts facts;
  std::unordered_map<std::string, size_t> usemtl_slot;  // name -> index in usemtl_names
  facts.text_for_tinyobj.reserve(file_text.size() + 64);
  AttributeCounts so_far;
  std::vector<std::array<double, 3>> positions;
  std::vector<LargeFace> large_faces;
  std::vector<std::string_view> tokens;
  int32_t current_usemtl = -1;
  UnusedAttributeIssues unused;
  for_each_obj_line(text, [&](std::string_view line, size_t number) {
    const size_t start = line.find_first_not_of(" \t");
    size_t rest = 0;
    const ObjStatement statement =
        start == std::string_view::npos ? ObjStatement::kOther : classify(line, start, &rest);
    if (statement != ObjStatement::kUsemtl) {
      facts.text_for_tinyobj += line;
      facts.text_for_tinyobj += '\n';
    }
    const LinePlace where{obj_path, number};
    switch (statement) {
      case ObjStatement::kOther:
        break;
      case ObjStatement::kVertex:
        split_blanks(line, rest, &tokens);
        positions.push_back(check_vertex(where, tokens));
        ++so_far.vertices;
        break;
      case ObjStatement::kTexcoord:
        split_blanks(line, rest, &tokens);
        check_texcoord(where, tokens);
        ++so_far.texcoords;
        break;
      case ObjStatement::kNormal:
        ++so_far.normals;
        break;
      case ObjStatement::kFace:
      case ObjStatement::kLine:
      case ObjStatement::kPoint: {
        const char* element = statement == ObjStatement::kFace   ? "face"
                              : statement == ObjStatement::kLine ? "line element"
                                                                 : "point element";
        split_blanks(line, rest, &tokens);
        if (statement == ObjStatement::kFace && tokens.size() < 3) {
          throw_input_error(where.text(), "face has " + std::to_string(tokens.size()) + " corners (need at least 3)");
        }
        for (const std::string_view corner : tokens) check_corner(where, element, corner, total, so_far, &unused);
        if (statement == ObjStatement::kFace && tokens.size() > kLargeFaceCorners) {
          LargeFace face{number, facts.text_for_tinyobj.size() - line.size() - 1, line.size(), current_usemtl, {}, {}};
          for (const std::string_view corner : tokens) {
            face.corners.push_back(corner_vertex(corner, so_far.vertices));
            face.texcoords.push_back(corner_texcoord(corner, total.texcoords, so_far.texcoords));
          }
          large_faces.push_back(std::move(face));
        }
        break;
      }
      case ObjStatement::kUsemtl: {
        // The whole rest of the line, as tinyobjloader reads "newmtl" (not "usemtl": it stops at
        // the first blank), so "usemtl Material #0" finds "newmtl Material #0".
        const size_t name_begin = line.find_first_not_of(" \t", rest);
        if (name_begin == std::string_view::npos) throw_input_error(where.text(), "usemtl without a material name");
        const std::string name(line.substr(name_begin, line.find_last_not_of(" \t") + 1 - name_begin));
        auto slot = usemtl_slot.find(name);
        if (slot == usemtl_slot.end()) {
          slot = usemtl_slot.emplace(name, facts.usemtl_names.size()).first;
          facts.usemtl_names.push_back({name, number});
        }
        facts.text_for_tinyobj += "usemtl " + usemtl_slot_token(slot->second) + "\n";
        current_usemtl = int32_t(slot->second);
        break;
      }
      case ObjStatement::kMtllib: {
        if (!check_mtllib) break;
        const std::vector<std::string> names = split_mtllib_names(std::string(line.substr(rest + 1)));
        bool any_opens = false;
        for (const std::string& name : names)
          any_opens = any_opens || !resolve_mtl_file(obj_dir, name).empty();
        if (names.empty()) throw_input_error(where.text(), "mtllib without a file name");
        if (!any_opens) {
          std::string tried;
          for (const std::string& name : names) tried += (tried.empty() ? "'" : " or '") + name + "'";
          throw_input_error(where.text(), "mtllib: cannot open " + tried);
        }
        break;
      }
    }
  });
  for (const LargeFace& face : large_faces) {
    if (is_convex_polygon(positions, face.corners)) {
      append_fan(face.corners, face.texcoords, face.usemtl, &facts.fan_triangles);
      facts.text_for_tinyobj.replace(face.text_offset, face.text_length, face.text_length, ' ');
    } else if (face.corners.size() > kMaxEarClippedCorners) {
      throw_input_error(file_line(obj_path, face.line),
                        "face of " + std::to_string(face.corners.size()) + " corners is not convex; faces of more than " +
                            std::to_string(kMaxEarClippedCorners) + " corners must be convex (split it)");
    }
  }
  if (unused.count > 0) {
    facts.warnings.push_back(single_line(
        unused.first + (unused.count > 1 ? " (and " + std::to_string(unused.count - 1) + " more)" : "") +
        "; ignored: such corners get texture coordinates (0, 0), and normals are not used"));
  }
  return facts;
}

}  // namespace pm
