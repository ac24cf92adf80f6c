// --frames parsing: ranges, steps, lists, order and duplicates, and every kind of bad spec.
#include <gtest/gtest.h>

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
      if (*spec) EXPECT_NE(message.find(std::string("'") + spec), std::string::npos) << message;
    }
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

}  // namespace
}  // namespace pm
