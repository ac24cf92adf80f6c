// Text metadata for PNG files: stb_image_write, which encodes the previews, writes no text
// chunks, so they are added to its encoded bytes here (PNG 1.2, section 11.3.4.3, tEXt).
// Declarations only.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace pm {

// One tEXt chunk as it goes into the file: 4-byte big-endian data length, "tEXt", the keyword,
// a NUL, the text, and the CRC-32 of type and data. The keyword must be 1 to 79 printable
// Latin-1 characters without leading, trailing or consecutive spaces, the text free of NUL;
// otherwise std::invalid_argument (both come from pmrender's code, never from input).
std::string png_text_chunk(const std::string& keyword, const std::string& text);

// Inserts one tEXt chunk per entry, in order, right after the IHDR chunk of an encoded PNG.
// std::invalid_argument when png does not start with the PNG signature and an IHDR chunk.
void add_png_text(std::string& png, const std::vector<std::pair<std::string, std::string>>& entries);

}  // namespace pm
