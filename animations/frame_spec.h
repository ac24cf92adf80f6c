// Frame selections as render farms write them: "1-30,47,100-200:2" (ranges inclusive, an
// optional :step). Parsed strictly; frames outside the sequence are an error, not skipped.
#pragma once

#include <string>
#include <vector>

namespace pm {

// The frames in the order given, duplicates removed (first occurrence kept). Throws InputError
// naming --frames and the offending part. Frames must lie in [first, last].
std::vector<int> parse_frame_spec(const std::string& spec, int first, int last);

}  // namespace pm
