// Output file name patterns: "out/cornell-box_####.exr" plus a frame number gives
// "out/cornell-box_0007.exr". Pure string work, no file system access.
#pragma once

#include <string>

namespace pm {

// Replaces every run of '#' with the frame number, zero-padded to the run's length ("####" and
// frame 7 -> "0007"). A frame needing more digits than the run has simply uses more ("##" and
// frame 123 -> "123"), so numbers are never cut. A pattern without '#' comes back unchanged; it
// is the caller's job to refuse such a pattern for several frames (see pattern_has_frame_field).
// A negative frame is a pm::InputError.
std::string expand_output_pattern(const std::string& pattern, int frame);

// True when the pattern contains at least one '#', i.e. different frames get different names.
bool pattern_has_frame_field(const std::string& pattern);

// "out/<scene>_####.exr", one file name whatever the scene file's name holds: '#' (a frame
// field), '/', '\\' and '.' (folders, "..", hidden files), NUL and other control characters
// become '_'; names longer than 119 bytes are cut at a character boundary; an empty name becomes
// "frame". Other bytes (UTF-8 letters, blanks) stay.
std::string default_output_pattern(const std::string& scene_name);

}  // namespace pm
