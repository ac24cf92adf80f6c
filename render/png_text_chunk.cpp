// tEXt chunks for encoded PNGs (png_text_chunk.h); the CRC-32 is zlib's, the one PNG specifies.
#include "render/png_text_chunk.h"

#include <zlib.h>

#include <cstdint>
#include <stdexcept>

namespace pm {

namespace {

const char kSignature[] = "\x89PNG\r\n\x1a\n";
const size_t kSignatureSize = 8;
const size_t kIhdrChunkSize = 4 + 4 + 13 + 4;  // length, type, 13 bytes of data, CRC

void append_big_endian(std::string& out, uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((value >> shift) & 0xffu));
}

bool printable_latin1(unsigned char c) { return (c >= 32 && c <= 126) || c >= 161; }

void check_keyword(const std::string& keyword) {
  bool ok = !keyword.empty() && keyword.size() <= 79 && keyword.front() != ' ' && keyword.back() != ' ' &&
            keyword.find("  ") == std::string::npos;
  for (unsigned char c : keyword) ok = ok && printable_latin1(c);
  if (!ok) throw std::invalid_argument("PNG text keyword '" + keyword + "' is not 1-79 printable Latin-1 characters");
}

}  // namespace

std::string png_text_chunk(const std::string& keyword, const std::string& text) {
  check_keyword(keyword);
  if (text.find('\0') != std::string::npos) throw std::invalid_argument("PNG text of '" + keyword + "' holds a NUL");
  std::string type_and_data = "tEXt" + keyword;
  type_and_data.push_back('\0');
  type_and_data += text;
  std::string chunk;
  append_big_endian(chunk, uint32_t(type_and_data.size() - 4));
  chunk += type_and_data;
  const uLong crc = crc32(crc32(0L, Z_NULL, 0), reinterpret_cast<const Bytef*>(type_and_data.data()),
                          uInt(type_and_data.size()));
  append_big_endian(chunk, uint32_t(crc));
  return chunk;
}

void add_png_text(std::string& png, const std::vector<std::pair<std::string, std::string>>& entries) {
  const bool has_ihdr = png.size() >= kSignatureSize + kIhdrChunkSize &&
                        png.compare(0, kSignatureSize, kSignature, kSignatureSize) == 0 &&
                        png.compare(kSignatureSize, 8, std::string("\0\0\0\x0dIHDR", 8)) == 0;
  if (!has_ihdr) throw std::invalid_argument("not a PNG starting with its IHDR chunk");
  std::string chunks;
  for (const auto& [keyword, text] : entries) chunks += png_text_chunk(keyword, text);
  png.insert(kSignatureSize + kIhdrChunkSize, chunks);
}

}  // namespace pm
