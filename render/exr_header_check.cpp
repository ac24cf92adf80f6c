// The EXR header walk (exr_header_check.h).
#include "render/exr_header_check.h"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <map>

#include "render/errors.h"

namespace pm {

namespace {

constexpr int64_t kMaxReadSide = 16384;  // the largest --resolution

// Walks EXR headers the way OpenEXR 3.1's Header::readFrom reads them: each attribute's value
// is read by its type's own reader, which for most types ignores the declared size (a chlist
// reads channels up to an empty name, a box2i reads 16 bytes), so the walk follows the same
// rules to stay where OpenEXR will be. Every length a reader would allocate is checked against
// the bytes left in the file.
class ExrHeaderWalk {
 public:
  explicit ExrHeaderWalk(const std::string& path) : path_(path), in_(path, std::ios::binary) {
    if (!in_) throw InputError("cannot read EXR file '" + path + "': " + std::strerror(errno));
    in_.seekg(0, std::ios::end);
    size_ = int64_t(in_.tellg());
    in_.seekg(0);
  }

  void check() {
    walk();
    // Checked once the whole header is read: OpenEXR sizes its line buffers from these.
    if (window_seen_) {
      if (width_ < 1 || height_ < 1 || width_ > kMaxReadSide || height_ > kMaxReadSide)
        fail("the data window is " + std::to_string(width_) + "x" + std::to_string(height_) + ", not within 1x1 to " +
             std::to_string(kMaxReadSide) + "x" + std::to_string(kMaxReadSide));
      if (tile_width_ > kMaxReadSide || tile_height_ > kMaxReadSide)
        fail("its tiles are " + std::to_string(tile_width_) + "x" + std::to_string(tile_height_) + ", larger than " +
             std::to_string(kMaxReadSide) + "x" + std::to_string(kMaxReadSide));
      // Tiled files decode a tile at a time, scanline files a chunk of lines. At most 16384 x
      // 16384 x (5 bytes a channel, channels bounded by the file size): no overflow.
      const int64_t line_buffer = tile_width_ > 0 ? tile_width_ * tile_height_ * bytes_per_pixel_
                                                  : width_ * bytes_per_pixel_ * lines_per_chunk();
      if (line_buffer > kMaxLineBufferBytes)
        fail("its " + std::to_string(channels_) + " channels make decoding buffers of " + std::to_string(line_buffer) +
             " bytes, more than " + std::to_string(kMaxLineBufferBytes));
    }
  }

 private:
  // Scanlines OpenEXR decompresses at once, by compression (ImfCompression.h order).
  int64_t lines_per_chunk() const {
    static const int kLines[] = {1, 1, 1, 16, 32, 16, 32, 32, 32, 256};  // NONE RLE ZIPS ZIP PIZ PXR24 B44 B44A DWAA DWAB
    return compression_ < 10 ? kLines[compression_] : 256;
  }

  void walk() {
    unsigned char start[8];
    if (!in_.read(reinterpret_cast<char*>(start), 8) || start[0] != 0x76 || start[1] != 0x2f || start[2] != 0x31 ||
        start[3] != 0x01)
      fail("not an OpenEXR file");
    // Version flags, bits 8-31 of the version field: long names (bit 10), multi-part (bit 12).
    max_name_ = (start[5] & 0x04) ? 255 : 31;
    const bool multipart = start[5] & 0x10;
    while (true) {
      const int attributes = walk_header();
      if (!multipart || attributes == 0) break;  // a multi-part file ends with an empty header
    }
  }

 private:
  [[noreturn]] void fail(const std::string& why) const { throw InputError("EXR file '" + path_ + "': " + why); }
  int64_t left() { return size_ - int64_t(in_.tellg()); }
  void need(int64_t bytes, const std::string& what) {
    if (bytes < 0 || bytes > left()) fail(what + " declares " + std::to_string(bytes) + " bytes, more than the file holds");
  }
  void skip(int64_t bytes, const std::string& what) {
    need(bytes, what);
    in_.seekg(bytes, std::ios::cur);
  }
  int32_t read_int(const std::string& what) {
    int32_t v = 0;
    if (!in_.read(reinterpret_cast<char*>(&v), 4)) fail(what + " is cut short");
    return v;
  }
  std::string read_name(const std::string& what) {
    std::string name;
    for (char c; in_.get(c);) {
      if (c == '\0') return name;
      if (int(name.size()) == max_name_) fail(what + " is longer than " + std::to_string(max_name_) + " characters");
      name += c;
    }
    fail("the header is cut short");
  }

  int walk_header() {
    int attributes = 0;
    while (true) {
      const std::string name = read_name("an attribute name");
      if (name.empty()) return attributes;
      const std::string type = read_name("an attribute type");
      const std::string what = "header attribute '" + name.substr(0, 40) + "'";
      const int32_t size = read_int(what);
      if (size < 0) fail(what + " has a negative size");
      walk_value(name, type, size, what);
      ++attributes;
    }
  }

  void walk_value(const std::string& name, const std::string& type, int32_t size, const std::string& what) {
    static const std::map<std::string, int> kFixedSizes = {
        {"box2i", 16}, {"box2f", 16}, {"chromaticities", 32}, {"compression", 1}, {"deepImageState", 1},
        {"double", 8}, {"envmap", 1}, {"float", 4}, {"int", 4}, {"keycode", 28}, {"lineOrder", 1},
        {"m33f", 36}, {"m33d", 72}, {"m44f", 64}, {"m44d", 128}, {"rational", 8}, {"tiledesc", 9},
        {"timecode", 8}, {"v2i", 8}, {"v2f", 8}, {"v2d", 16}, {"v3i", 12}, {"v3f", 12}, {"v3d", 24}};
    const auto fixed = kFixedSizes.find(type);
    if (name == "dataWindow" && type == "box2i") {
      const int64_t x0 = read_int(what), y0 = read_int(what), x1 = read_int(what), y1 = read_int(what);
      width_ = x1 - x0 + 1;
      height_ = y1 - y0 + 1;
      window_seen_ = true;
    } else if (name == "tiles" && type == "tiledesc") {
      tile_width_ = uint32_t(read_int(what));
      tile_height_ = uint32_t(read_int(what));
      skip(1, what);  // level and rounding mode
    } else if (name == "compression" && type == "compression") {
      char c = 0;
      if (!in_.get(c)) fail(what + " is cut short");
      compression_ = static_cast<unsigned char>(c);
    } else if (fixed != kFixedSizes.end()) {
      skip(fixed->second, what);
    } else if (type == "chlist") {
      // Channels: a name, then pixel type (UINT, HALF, FLOAT), pLinear + 3 reserved bytes, x and y
      // sampling.
      while (!read_name("a channel name").empty()) {
        const int32_t pixel_type = read_int(what);
        skip(4, what);
        const int32_t x_sampling = read_int(what);
        skip(4, what);
        bytes_per_pixel_ += (pixel_type == 1 ? 2 : 4) / std::max(1, x_sampling) + 1;
        ++channels_;
      }
    } else if (type == "preview") {
      // width x height RGBA bytes follow; divided rather than multiplied, which could overflow.
      const uint32_t width = uint32_t(read_int(what)), height = uint32_t(read_int(what));
      if (width > 0 && uint64_t(height) > uint64_t(left()) / 4 / width) fail(what + ": the preview is larger than the file");
      skip(int64_t(width) * int64_t(height) * 4, what);
    } else if (type == "stringvector") {
      need(size, what);
      for (int64_t read = 0; read < size;) {
        const int32_t length = read_int(what);
        skip(length, what);
        read += 4 + int64_t(length);
      }
    } else if (type == "idmanifest") {
      fail(what + " is an ID manifest, which pmrender does not read");
    } else {
      skip(size, what);  // string, floatvector and unknown types: exactly the declared size
    }
  }

  static constexpr int64_t kMaxLineBufferBytes = int64_t(256) << 20;

  std::string path_;
  std::ifstream in_;
  int64_t size_ = 0;
  int max_name_ = 31;
  bool window_seen_ = false;
  int64_t width_ = 0, height_ = 0, bytes_per_pixel_ = 0, channels_ = 0, tile_width_ = 0, tile_height_ = 0;
  unsigned compression_ = 0;
};

}  // namespace

void check_exr_header(const std::string& path) { ExrHeaderWalk(path).check(); }

}  // namespace pm
