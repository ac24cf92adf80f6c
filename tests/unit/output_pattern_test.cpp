// Tests of render/output_pattern: '#' runs become zero-padded frame numbers, longer numbers are
// never cut, several runs, patterns without a run, negative frames, the default pattern.
#include "render/output_pattern.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "render/errors.h"

namespace pm {
namespace {

TEST(OutputPattern, RunIsZeroPaddedToItsLength) {
  EXPECT_EQ(expand_output_pattern("out/cornell-box_####.exr", 7), "out/cornell-box_0007.exr");
  EXPECT_EQ(expand_output_pattern("f_#.exr", 0), "f_0.exr");
  EXPECT_EQ(expand_output_pattern("f_######.exr", 42), "f_000042.exr");
}

TEST(OutputPattern, LongerNumbersUseMoreDigits) {
  EXPECT_EQ(expand_output_pattern("f_##.exr", 123), "f_123.exr");
  EXPECT_EQ(expand_output_pattern("f_####.exr", 1234), "f_1234.exr");
  EXPECT_EQ(expand_output_pattern("f_####.exr", 2147483647), "f_2147483647.exr");
}

TEST(OutputPattern, EveryRunIsExpanded) {
  EXPECT_EQ(expand_output_pattern("shot_##/frame_####.exr", 5), "shot_05/frame_0005.exr");
  EXPECT_EQ(expand_output_pattern("#_#", 3), "3_3");
  EXPECT_EQ(expand_output_pattern("####", 12), "0012");
}

TEST(OutputPattern, PatternWithoutRunIsUnchanged) {
  EXPECT_EQ(expand_output_pattern("out/still.exr", 9), "out/still.exr");
  EXPECT_EQ(expand_output_pattern("", 9), "");
  EXPECT_FALSE(pattern_has_frame_field("out/still.exr"));
  EXPECT_TRUE(pattern_has_frame_field("out/still_#.exr"));
}

TEST(OutputPattern, NegativeFrameIsAnInputError) {
  EXPECT_THROW(expand_output_pattern("f_####.exr", -1), InputError);
}

TEST(OutputPattern, DefaultPatternNamesTheScene) {
  EXPECT_EQ(default_output_pattern("cornell-box"), "out/cornell-box_####.exr");
  EXPECT_EQ(expand_output_pattern(default_output_pattern("sponza"), 3), "out/sponza_0003.exr");
}

TEST(OutputPattern, DefaultPatternKeepsSceneNameFromChangingThePattern) {
  EXPECT_EQ(default_output_pattern("take#2"), "out/take_2_####.exr");
  EXPECT_EQ(default_output_pattern("a/b"), "out/a_b_####.exr");
  EXPECT_EQ(default_output_pattern(""), "out/frame_####.exr");
}

TEST(OutputPattern, DefaultPatternIsOneSafeFileNameForAnySceneName) {
  using namespace std::string_literals;
  // A NUL used to cut the path short, so every frame overwrote one extension-less file.
  EXPECT_EQ(default_output_pattern("a\0b"s), "out/a_b_####.exr");
  EXPECT_EQ(default_output_pattern("line\nbreak\r\t"), "out/line_break___####.exr");
  EXPECT_EQ(default_output_pattern(".."), "out/___####.exr");
  EXPECT_EQ(default_output_pattern("../../etc/x"), "out/______etc_x_####.exr");
  EXPECT_EQ(default_output_pattern(".hidden"), "out/_hidden_####.exr");
  EXPECT_EQ(default_output_pattern("K\xc3\xbc" "che 2"), "out/K\xc3\xbc" "che 2_####.exr");  // UTF-8 and blanks stay
  // Long names are cut (at a character boundary) so the file name fits beside its temporary.
  std::string long_name;
  for (int i = 0; i < 200; ++i) long_name += "\xc3\xbc";
  const std::string pattern = default_output_pattern(long_name);
  const std::string file = pattern.substr(4);
  EXPECT_LE(file.size(), 128u);
  EXPECT_EQ(file.substr(file.size() - 9), "_####.exr");
  EXPECT_EQ((file.size() - 9) % 2, 0u);  // no half of a two-byte character
  EXPECT_EQ(std::count(pattern.begin(), pattern.end(), '/'), 1);
}

}  // namespace
}  // namespace pm
