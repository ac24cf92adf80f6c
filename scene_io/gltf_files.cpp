// glTF file access rules (gltf_files.h): pre-checks of the file and its buffers, tinygltf's file
// system callbacks, and shortened tinygltf messages.
#include "scene_io/gltf_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <vector>

#include "scene_io/json_reader.h"
#include "scene_io/load_error.h"
#include "scene_io/regular_files.h"

namespace pm {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

// A name from the file as quoted in a message: at most 80 characters, control characters '?'.
std::string shown(const std::string& text) {
  std::string out = text.size() > 80 ? text.substr(0, 77) + "..." : text;
  for (char& c : out)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return "'" + out + "'";
}

// tinygltf decodes %XX escapes in buffer URIs before opening them (glTF URIs are URI-encoded).
std::string percent_decoded(const std::string& uri) {
  std::string out;
  for (size_t i = 0; i < uri.size(); ++i) {
    if (uri[i] == '%' && i + 2 < uri.size() && std::isxdigit(static_cast<unsigned char>(uri[i + 1])) &&
        std::isxdigit(static_cast<unsigned char>(uri[i + 2]))) {
      out += char(std::stoi(uri.substr(i + 1, 2), nullptr, 16));
      i += 2;
    } else {
      out += uri[i];
    }
  }
  return out;
}

// The JSON text of a .gltf, or the JSON chunk of a .glb ("" when the container is malformed:
// tinygltf reports that itself).
std::string json_text(const std::string& path, const std::vector<unsigned char>& bytes) {
  const bool glb = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  if (!glb) return std::string(bytes.begin(), bytes.end());
  if (bytes.size() < 20) return "";
  uint32_t chunk_length = 0, chunk_type = 0;
  std::memcpy(&chunk_length, bytes.data() + 12, 4);
  std::memcpy(&chunk_type, bytes.data() + 16, 4);
  if (chunk_type != 0x4E4F534Au || chunk_length > bytes.size() - 20) return "";
  return std::string(bytes.begin() + 20, bytes.begin() + 20 + chunk_length);
}

// The number of bytes a base64 payload decodes to; -1 when it is not base64.
int64_t base64_decoded_size(const std::string& payload) {
  if (payload.size() % 4 != 0) return -1;
  size_t padding = 0;
  for (size_t i = 0; i < payload.size(); ++i) {
    const char c = payload[i];
    const bool letter = (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '+' || c == '/';
    if (c == '=' && i + 2 >= payload.size()) ++padding;
    else if (!letter || padding > 0) return -1;
  }
  return int64_t(payload.size() / 4 * 3) - int64_t(padding);
}

void check_buffer(const std::string& path, const fs::path& folder, const json& buffer, size_t index) {
  const std::string where = path + ": buffers[" + std::to_string(index) + "]";
  if (!buffer.is_object()) return;  // tinygltf names that
  const auto length_field = buffer.find("byteLength");
  if (length_field == buffer.end() || !length_field->is_number_integer() || length_field->get<int64_t>() < 1)
    throw_input_error(where + ".byteLength", "expected a whole number of bytes, at least 1");
  const int64_t length = length_field->get<int64_t>();
  const auto uri_field = buffer.find("uri");
  if (uri_field == buffer.end()) return;  // the GLB's own BIN chunk
  if (!uri_field->is_string()) throw_input_error(where + ".uri", "expected a string");
  const std::string uri = uri_field->get<std::string>();

  if (uri.rfind("data:", 0) == 0) {
    const size_t comma = uri.find(',');
    if (comma == std::string::npos || uri.rfind(";base64", comma) != comma - 7)
      throw_input_error(where + ".uri", "a data URI must be base64 (data:application/octet-stream;base64,...)");
    const int64_t size = base64_decoded_size(uri.substr(comma + 1));
    if (size < 0) throw_input_error(where + ".uri", "the data URI is not valid base64");
    if (size != length)
      throw_input_error(where + ".byteLength",
                        std::to_string(length) + ", but its data URI holds " + std::to_string(size) + " bytes");
    return;
  }
  const std::string name = percent_decoded(uri);
  if (name.empty()) throw_input_error(where + ".uri", "is empty");
  const fs::path file = fs::path(name).is_absolute() ? fs::path(name) : folder / name;
  off_t size = 0;
  const std::string problem = file_problem(file.string(), &size);
  if (!problem.empty())
    throw_input_error(where + ".uri", shown(uri) + " " + problem + (problem == "not found" ? " (looked for " + shown(file.string()) + ")" : ""));
  if (int64_t(size) != length)
    throw_input_error(where + ".byteLength",
                      std::to_string(length) + ", but " + shown(uri) + " has " + std::to_string(size) + " bytes");
}

// tinygltf joins every URI to the glTF's folder (and then to "."), absolute ones too: undo that.
std::string expand_path(const std::string& joined, void* user_data) {
  const std::string& gltf_path = *static_cast<const std::string*>(user_data);
  const size_t slash = gltf_path.find_last_of("/\\");
  const std::string folder = slash == std::string::npos ? "" : gltf_path.substr(0, slash);
  for (const std::string& base : {folder, std::string(".")}) {
    if (base.empty()) continue;
    const std::string prefix = base.back() == '/' ? base : base + "/";
    if (joined.size() > prefix.size() && joined.compare(0, prefix.size(), prefix) == 0 && joined[prefix.size()] == '/')
      return joined.substr(prefix.size());
  }
  return joined;
}

bool regular_file_exists(const std::string& path, void*) {
  off_t size = 0;
  return file_problem(path, &size).empty();
}

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  const std::string problem = read_regular_file(path, out);
  if (!problem.empty() && err) *err += shown(path) + " " + problem + "\n";
  return problem.empty();
}

bool refuse_to_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "pmrender does not write glTF files\n";
  return false;
}

}  // namespace

void check_gltf_files(const std::string& path) {
  std::vector<unsigned char> bytes;
  const std::string problem = read_regular_file(path, &bytes);
  if (!problem.empty())
    throw_input_error(path, problem.find("regular file") != std::string::npos ? problem : "cannot open (" + problem + ")");
  const std::string text = json_text(path, bytes);
  check_json_nesting(path, text);
  const json document = json::parse(text, nullptr, /*allow_exceptions=*/false);
  if (document.is_discarded() || !document.is_object()) return;  // tinygltf reports the syntax
  const auto buffers = document.find("buffers");
  if (buffers == document.end() || !buffers->is_array()) return;
  const fs::path folder = fs::path(path).parent_path();
  for (size_t i = 0; i < buffers->size(); ++i) check_buffer(path, folder, (*buffers)[i], i);
}

tinygltf::FsCallbacks regular_file_callbacks(const std::string* gltf_path) {
  tinygltf::FsCallbacks callbacks;
  callbacks.FileExists = regular_file_exists;
  callbacks.ExpandFilePath = expand_path;
  callbacks.ReadWholeFile = read_whole_file;
  callbacks.WriteWholeFile = refuse_to_write;
  callbacks.user_data = const_cast<std::string*>(gltf_path);
  return callbacks;
}

std::string short_tinygltf_message(const std::string& text) {
  std::string joined;
  size_t start = 0;
  while (start <= text.size()) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    std::string line = text.substr(start, end - start);
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r')) line.pop_back();
    if (!line.empty()) joined += (joined.empty() ? "" : "; ") + line;
    start = end + 1;
  }
  std::string out;
  for (size_t i = 0; i < joined.size();) {
    if (joined.compare(i, 5, "data:") == 0) {
      size_t end = i;
      while (end < joined.size() && joined[end] != ' ' && joined[end] != '\'' && joined[end] != '"')
        ++end;
      out += "data:... (" + std::to_string(end - i) + " characters)";
      i = end;
    } else {
      out += joined[i++];
    }
  }
  if (out.size() > 300) out = out.substr(0, 297) + "...";
  return out;
}

}  // namespace pm
