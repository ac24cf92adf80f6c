// --frames parsing: ranges, steps, lists, order and duplicates, and every kind of bad spec; and
// writing frames back as a short specification that parses to the same frames.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>

#include "scene_io/frame_spec.h"
#include "render/errors.h"

namespace pm {
namespace {

TEST(FrameSpec, ParsesRangesStepsAndSingles) {
  EXPECT_EQ(parse_frame_spec("1-3,7,10-16:3", 0, 100), (std::vector<int>{1, 2, 3, 7, 10, 13, 16}));
  EXPECT_EQ(parse_frame_spec("0", 0, 0), (std::vector<int>{0}));
  EXPECT_EQ(parse_frame_spec("5-9:10", 0, 10), (std::vector<int>{5}));
}

TEST(FrameSpec, KeepsGivenOrderAndDropsDuplicates) {
  EXPECT_EQ(parse_frame_spec("9,2-4,3", 0, 10), (std::vector<int>{9, 2, 3, 4}));
}

TEST(FrameSpec, RejectsMalformedSpecsNamingThePart) {
  for (const char* spec : {"", "1-", "-3", "a", "1,,2", "3-1", "1-5:0", "4:2", "1-5:x", "1.5", " 1", "1-2-3"}) {
    try {
      parse_frame_spec(spec, 0, 100);
      ADD_FAILURE() << "accepted '" << spec << "'";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_EQ(message.find("--frames"), std::string::npos) << "the library names no option: " << message;
      if (*spec) {
        EXPECT_NE(message.find(std::string("'") + spec), std::string::npos) << message;
      }
    }
  }
}

// A spec with line breaks or control characters (found by the fuzzer: "\0\n1-") is quoted
// escaped, so its message stays one printable line.
TEST(FrameSpec, ControlCharactersAreEscapedInMessages) {
  try {
    parse_frame_spec(std::string("\0\n1-", 4), 0, 100);
    ADD_FAILURE() << "accepted a spec with a NUL and a line break";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), "'\\x00\\n1-': expected a frame number, got '\\x00\\n1'");
  }
}

TEST(FrameSpec, FramesOutsideTheSequenceAreErrors) {
  EXPECT_THROW(parse_frame_spec("0-24", 0, 23), InputError);
  EXPECT_THROW(parse_frame_spec("5", 10, 20), InputError);
  try {
    parse_frame_spec("20-30", 0, 23);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("0-23"), std::string::npos) << e.what();
  }
}

TEST(FrameSpec, FormatWritesRunsCompactly) {
  EXPECT_EQ(format_frame_spec({}), "");
  EXPECT_EQ(format_frame_spec({7}), "7");
  EXPECT_EQ(format_frame_spec({0, 1}), "0-1");
  EXPECT_EQ(format_frame_spec({1, 2, 3, 4, 10, 20, 30, 7}), "1-4,10-30:10,7");
  EXPECT_EQ(format_frame_spec({4, 9}), "4,9");
  EXPECT_EQ(format_frame_spec({9, 8, 7}), "9,8,7");
  EXPECT_EQ(format_frame_spec({100, 102, 104, 105, 106}), "100-104:2,105-106");
  EXPECT_EQ(format_frame_spec({999999998, 999999999}), "999999998-999999999");
}

TEST(FrameSpec, FormatThenParseGivesTheFramesBack) {
  std::mt19937 random(7);
  for (int trial = 0; trial < 500; ++trial) {
    // Distinct frames in random order with runs of random steps mixed in.
    std::vector<int> frames;
    const int pieces = 1 + int(random() % 6);
    for (int p = 0; p < pieces; ++p) {
      const int start = int(random() % 200), step = 1 + int(random() % 4), count = 1 + int(random() % 8);
      for (int k = 0; k < count; ++k)
        if (std::find(frames.begin(), frames.end(), start + k * step) == frames.end()) frames.push_back(start + k * step);
    }
    if (trial % 3 == 0) std::shuffle(frames.begin(), frames.end(), random);
    const std::string spec = format_frame_spec(frames);
    EXPECT_EQ(parse_frame_spec(spec, 0, 1000), frames) << spec;
  }
}

}  // namespace
}  // namespace pm
