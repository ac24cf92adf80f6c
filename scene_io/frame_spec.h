// Frame selections as render farms write them: "1-30,47,100-200:2" (ranges inclusive, an
// optional :step). Parsed strictly; frames outside the sequence are an error, not skipped; and
// written back compactly (a farm task's chunk of frames as one short specification).
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

// The shortest-form specification of these frames in this order, runs of equal steps as A-B or
// A-B:STEP, e.g. {1,2,3,4,10,20,30,7} -> "1-4,10-30:10,7". parse_frame_spec of the result gives
// the frames back. Frames must be non-negative and distinct; an empty list gives "".
std::string format_frame_spec(const std::vector<int>& frames);

}  // namespace pm
