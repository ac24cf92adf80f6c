// Frame selections as render farms write them: "1-30,47,100-200:2" (ranges inclusive, an
// optional :step). Parsed strictly; frames outside the sequence are an error, not skipped.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace pm {

// The most frames one specification may select.
constexpr size_t kMaxFrameSpecFrames = 1000000;

// The frames in the order given, duplicates removed (first occurrence kept). Throws InputError
// naming the offending part (the command line adds the option's name). Frames must lie in
// [first, last]; at most kMaxFrameSpecFrames of them.
std::vector<int> parse_frame_spec(const std::string& spec, int first, int last);

}  // namespace pm
