// tEXt chunks added to encoded PNGs: the exact bytes of a chunk (CRC-32 included, against a value
// computed independently), the place they go in the file, and the refusal of what the PNG
// format forbids.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>

#include "render/png_text_chunk.h"

namespace pm {
namespace {

TEST(PngTextChunk, BytesAreLengthTypeKeywordNulTextCrc) {
  // CRC-32 of "tEXtTitle\0pmrender" is 0xa57b8c93 (zlib.crc32 in Python, ISO 3309 polynomial).
  const std::string expected("\0\0\0\x0etEXtTitle\0pmrender\xa5\x7b\x8c\x93", 26);
  EXPECT_EQ(png_text_chunk("Title", "pmrender"), expected);
}

TEST(PngTextChunk, ChunksGoRightAfterIhdrInOrder) {
  const std::string signature("\x89PNG\r\n\x1a\n", 8);
  const std::string ihdr("\0\0\0\x0dIHDR\0\0\0\x01\0\0\0\x01\x08\x02\0\0\0\x90\x77\x53\xde", 25);
  const std::string rest("\0\0\0\0IEND\xae\x42\x60\x82", 12);
  std::string png = signature + ihdr + rest;
  add_png_text(png, {{"a", "1"}, {"b", "2"}});
  EXPECT_EQ(png, signature + ihdr + png_text_chunk("a", "1") + png_text_chunk("b", "2") + rest);
}

TEST(PngTextChunk, WhatThePngFormatForbidsIsRefused) {
  EXPECT_THROW(png_text_chunk("", "x"), std::invalid_argument);
  EXPECT_THROW(png_text_chunk(std::string(80, 'k'), "x"), std::invalid_argument);
  EXPECT_THROW(png_text_chunk(" lead", "x"), std::invalid_argument);
  EXPECT_THROW(png_text_chunk("two  spaces", "x"), std::invalid_argument);
  EXPECT_THROW(png_text_chunk(std::string("nul\0", 4), "x"), std::invalid_argument);
  EXPECT_THROW(png_text_chunk("k", std::string("a\0b", 3)), std::invalid_argument);
  EXPECT_NO_THROW(png_text_chunk(std::string(79, 'k'), ""));
  std::string not_png = "GIF89a and more bytes than a PNG header needs";
  EXPECT_THROW(add_png_text(not_png, {{"a", "1"}}), std::invalid_argument);
}

}  // namespace
}  // namespace pm
