// Owns strict JSON parsing for scene files (a SAX handler that builds the document, tracks field
// paths and refuses duplicate keys) and JsonField's typed reads with file + field-path errors.
#include "scene_io/json_reader.h"

#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "scene_io/load_error.h"

namespace pm {
namespace {

using nlohmann::json;

std::string join_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}

// Builds the document from SAX events. We use SAX rather than json::parse because only the SAX
// error callback receives the input position for every failure (json::parse throws number
// overflow as out_of_range without one), and because it lets us see each key as it arrives.
class StrictDocumentBuilder : public nlohmann::json_sax<json> {
 public:
  json document;
  // Set when parsing stopped early.
  bool failed = false;
  bool duplicate_key = false;
  size_t error_position = 0;  // characters read when the error was detected
  int error_id = 0;           // nlohmann exception id (101 syntax, 406 number overflow, ...)
  std::string error_text;
  std::string error_path;  // field being read when the error happened

  bool null() override { return add(json(nullptr)); }
  bool boolean(bool v) override { return add(json(v)); }
  bool number_integer(number_integer_t v) override { return add(json(v)); }
  bool number_unsigned(number_unsigned_t v) override { return add(json(v)); }
  bool number_float(number_float_t v, const string_t&) override { return add(json(v)); }
  bool string(string_t& v) override { return add(json(v)); }
  bool binary(binary_t& v) override { return add(json(v)); }

  bool start_object(std::size_t) override { return open(json::object()); }
  bool start_array(std::size_t) override { return open(json::array()); }
  bool end_object() override { return close(); }
  bool end_array() override { return close(); }

  bool key(string_t& k) override {
    Frame& frame = open_containers_.back();
    if (frame.node->contains(k)) {
      failed = true;
      duplicate_key = true;
      error_path = join_path(frame.path, k);
      return false;
    }
    pending_key_ = k;
    return true;
  }

  bool parse_error(std::size_t position, const std::string&, const json::exception& ex) override {
    failed = true;
    error_position = position;
    error_id = ex.id;
    error_text = ex.what();
    error_path = path_of_next_value();
    return false;
  }

 private:
  struct Frame {
    json* node;
    std::string path;
  };

  std::string path_of_next_value() const {
    if (open_containers_.empty()) return "";
    const Frame& frame = open_containers_.back();
    if (frame.node->is_array()) return frame.path + "[" + std::to_string(frame.node->size()) + "]";
    return join_path(frame.path, pending_key_);
  }

  // Places a value where the parser is: the root, the next array slot, or the pending key.
  json* place(json&& value) {
    if (open_containers_.empty()) {
      document = std::move(value);
      return &document;
    }
    json& parent = *open_containers_.back().node;
    if (parent.is_array()) {
      parent.push_back(std::move(value));
      return &parent.back();
    }
    json& slot = parent[pending_key_];
    slot = std::move(value);
    return &slot;
  }

  bool add(json&& value) {
    place(std::move(value));
    return true;
  }

  bool open(json&& container) {
    std::string path = path_of_next_value();
    // Pointers stay valid: a container's parent gets no new element until the container closes.
    json* node = place(std::move(container));
    open_containers_.push_back({node, std::move(path)});
    return true;
  }

  bool close() {
    open_containers_.pop_back();
    return true;
  }

  std::vector<Frame> open_containers_;
  std::string pending_key_;
};

// nlohmann's what() reads "[json.exception.parse_error.101] parse error at line 3, column 5:
// syntax error ..."; we print our own line number, so keep only the part after those prefixes.
std::string strip_nlohmann_prefixes(std::string text) {
  if (!text.empty() && text[0] == '[') {
    size_t end = text.find("] ");
    if (end != std::string::npos) text = text.substr(end + 2);
  }
  const std::string located = "parse error at line ";
  if (text.compare(0, located.size(), located) == 0) {
    size_t colon = text.find(": ");
    if (colon != std::string::npos) text = text.substr(colon + 2);
  } else if (text.compare(0, 12, "parse error:") == 0) {
    text = text.substr(12);
    if (!text.empty() && text[0] == ' ') text = text.substr(1);
  }
  return text;
}

// nlohmann reports how many characters it had read; the offending character is the last of them.
size_t line_of_position(const std::string& text, size_t chars_read) {
  size_t end = chars_read == 0 ? 0 : std::min(chars_read - 1, text.size());
  size_t line = 1;
  for (size_t i = 0; i < end; ++i) {
    if (text[i] == '\n') ++line;
  }
  return line;
}

const char* kind_of(const json& value) {
  switch (value.type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return value.get<bool>() ? "true" : "false";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return "an array";
    case json::value_t::object:
      return "an object";
    default:
      return "a value";
  }
}

}  // namespace

void check_json_nesting(const std::string& file, const std::string& text) {
  int depth = 0;
  size_t line = 1;
  bool in_string = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (c == '\n') ++line;
    if (in_string) {
      if (c == '\\') ++i;  // the escaped character cannot end the string
      else if (c == '"') in_string = false;
    } else if (c == '"') {
      in_string = true;
    } else if (c == '[' || c == '{') {
      if (++depth > kMaxJsonNesting)
        throw_input_error(file_line(file, line), "JSON nested deeper than " + std::to_string(kMaxJsonNesting) + " levels");
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

nlohmann::json parse_json_file_strict(const std::string& path) {
  std::error_code ec;
  // Devices and pipes (/dev/zero, a FIFO) would be read without end.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    throw_input_error(path, "not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw_input_error(path, std::string("cannot open (") + std::strerror(errno) + ")");
  std::ostringstream buffer;
  buffer << in.rdbuf();
  const std::string text = buffer.str();
  check_json_nesting(path, text);

  StrictDocumentBuilder builder;
  json::sax_parse(text, &builder);
  if (!builder.failed) return std::move(builder.document);

  if (builder.duplicate_key) throw_input_error(path + ": " + builder.error_path, "duplicate key");
  const std::string where = file_line(path, line_of_position(text, builder.error_position));
  if (builder.error_id == 406) {  // a number beyond double range, e.g. 1e999
    std::string literal = builder.error_text;
    size_t open_quote = literal.find('\'');
    size_t close_quote = literal.rfind('\'');
    if (open_quote != std::string::npos && close_quote > open_quote) {
      literal = literal.substr(open_quote + 1, close_quote - open_quote - 1);
    }
    throw_input_error(where + ": " + builder.error_path, "expected a finite number, got " + literal);
  }
  throw_input_error(where, "JSON parse error: " + strip_nlohmann_prefixes(builder.error_text));
}

std::string describe_json_value(const nlohmann::json& value) {
  if (value.is_number_float()) {
    double v = value.get<double>();
    if (std::isnan(v)) return "nan";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    return value.dump();
  }
  if (value.is_number()) return value.dump();
  return kind_of(value);
}

JsonField::JsonField(std::string file, const nlohmann::json& value, std::string path)
    : file_(std::move(file)), value_(&value), path_(std::move(path)) {}

void JsonField::fail(const std::string& message) const {
  throw_input_error(path_.empty() ? file_ : file_ + ": " + path_, message);
}

std::string JsonField::child_path(const std::string& key) const { return join_path(path_, key); }

void JsonField::expect_object_with_keys(const std::vector<std::string>& allowed_keys) const {
  if (!value_->is_object()) fail("expected an object, got " + describe_json_value(*value_));
  for (const auto& item : value_->items()) {
    bool known = false;
    for (const std::string& allowed : allowed_keys) known = known || item.key() == allowed;
    if (known) continue;
    std::string list;
    for (const std::string& allowed : allowed_keys) list += (list.empty() ? "" : ", ") + allowed;
    JsonField(file_, item.value(), child_path(item.key()))
        .fail("unknown key (expected one of: " + list + ")");
  }
}

bool JsonField::has(const std::string& key) const { return value_->is_object() && value_->contains(key); }

JsonField JsonField::member(const std::string& key) const {
  if (!value_->is_object()) fail("expected an object, got " + describe_json_value(*value_));
  auto it = value_->find(key);
  if (it == value_->end()) throw_input_error(file_ + ": " + child_path(key), "missing required key");
  return JsonField(file_, *it, child_path(key));
}

size_t JsonField::expect_array(size_t size) const {
  if (!value_->is_array()) fail("expected an array, got " + describe_json_value(*value_));
  if (size != kAnySize && value_->size() != size) {
    fail("expected an array of " + std::to_string(size) + " elements, got " + std::to_string(value_->size()));
  }
  return value_->size();
}

JsonField JsonField::element(size_t index) const {
  return JsonField(file_, value_->at(index), path_ + "[" + std::to_string(index) + "]");
}

double JsonField::finite_number() const {
  if (!value_->is_number()) fail("expected a finite number, got " + describe_json_value(*value_));
  double v = value_->get<double>();
  if (!std::isfinite(v)) fail("expected a finite number, got " + describe_json_value(*value_));
  return v;
}

long long JsonField::integer_in(long long lo, long long hi) const {
  const std::string expected =
      "expected an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got ";
  if (!value_->is_number()) fail(expected + describe_json_value(*value_));
  double as_double = value_->get<double>();
  // Compare in double first so huge values cannot overflow the integer conversion.
  if (!std::isfinite(as_double) || std::floor(as_double) != as_double ||
      as_double < static_cast<double>(lo) || as_double > static_cast<double>(hi)) {
    fail(expected + describe_json_value(*value_));
  }
  return static_cast<long long>(as_double);
}

std::string JsonField::non_empty_string() const {
  if (!value_->is_string()) fail("expected a string, got " + describe_json_value(*value_));
  std::string s = value_->get<std::string>();
  if (s.empty()) fail("expected a non-empty string");
  return s;
}

Float3 JsonField::float3() const {
  expect_array(3);
  double v[3];
  for (size_t i = 0; i < 3; ++i) {
    JsonField component = element(i);
    v[i] = component.finite_number();
    if (std::fabs(v[i]) > FLT_MAX) {
      component.fail("value " + describe_json_value(component.value()) + " is beyond float range");
    }
  }
  return Float3{static_cast<float>(v[0]), static_cast<float>(v[1]), static_cast<float>(v[2])};
}

}  // namespace pm
