// The tEXt chunks of a PNG file as a keyword -> text map, read the way a PNG reader walks the
// file (signature, then length-type-data-CRC chunks up to IEND), with every chunk's CRC-32
// checked, so a test of a preview's metadata also proves the file around it is well formed.
#pragma once

#include <gtest/gtest.h>
#include <zlib.h>

#include <cstdint>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

namespace pm::test {

inline uint32_t big_endian_at(const std::string& bytes, size_t at) {
  return uint32_t(uint8_t(bytes[at])) << 24 | uint32_t(uint8_t(bytes[at + 1])) << 16 |
         uint32_t(uint8_t(bytes[at + 2])) << 8 | uint32_t(uint8_t(bytes[at + 3]));
}

// Empty map and a test failure when the file is not a well-formed PNG up to its IEND.
inline std::map<std::string, std::string> png_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  std::map<std::string, std::string> text;
  if (bytes.compare(0, 8, "\x89PNG\r\n\x1a\n", 8) != 0) {
    ADD_FAILURE() << path << ": no PNG signature";
    return {};
  }
  for (size_t at = 8; at + 12 <= bytes.size();) {
    const uint32_t length = big_endian_at(bytes, at);
    if (at + 12 + size_t(length) > bytes.size()) break;
    const std::string type = bytes.substr(at + 4, 4), data = bytes.substr(at + 8, length);
    const uLong crc = crc32(0L, reinterpret_cast<const Bytef*>(bytes.data() + at + 4), uInt(4 + length));
    if (uint32_t(crc) != big_endian_at(bytes, at + 8 + length)) {
      ADD_FAILURE() << path << ": bad CRC in chunk " << type;
      return {};
    }
    if (type == "IEND") return text;
    if (type == "tEXt") {
      const size_t nul = data.find('\0');
      if (nul == std::string::npos) {
        ADD_FAILURE() << path << ": tEXt chunk without a NUL after its keyword";
        return {};
      }
      text[data.substr(0, nul)] = data.substr(nul + 1);
    }
    at += 12 + length;
  }
  ADD_FAILURE() << path << ": no IEND chunk";
  return {};
}

}  // namespace pm::test
