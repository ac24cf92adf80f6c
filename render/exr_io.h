// OpenEXR output and input of FrameImage. Only declarations here: OpenEXR's headers stay inside
// exr_io.cpp because Imath's half clashes with CUDA's, and this header may reach .cu files
// through others.
#pragma once

#include <string>

#include "render/image.h"

namespace pm {

// Writes the image as a scanline OpenEXR file with ZIP compression. Channels are HALF unless
// full_float is true, then FLOAT. Layers become channel prefixes (combined = R,G,B; "direct" =
// direct.R, direct.G, direct.B); data layers follow with their own channel names (N.X, Z),
// FLOAT where the layer asks for it; each attribute becomes a string attribute in the header.
//
// - Any NaN or Inf in any layer is refused (pm::DeviceError "refusing to write NaN/Inf ...").
//   The renderer guarantees finite output; this is the last guard before the file.
// - In half mode, values beyond the half range (+-65504) are clamped to it instead of becoming
//   Inf. Use full_float for images that really are that bright.
// - The write is atomic: the data goes to a hidden temporary file in the target's folder, is
//   flushed to disk, and is then renamed onto the target. Missing parent folders are created.
//   On any failure the temporary is removed, an existing target is left untouched, and
//   pm::DeviceError is thrown naming the path (exit code 1: an output failure, not bad input).
// - A malformed FrameImage (zero size, wrong rgb length, duplicate or no layers) is also a
//   pm::DeviceError: it is a bug in the caller, not the user's input.
void write_exr(const std::string& path, const FrameImage& image, bool full_float);

// What writing the image with half channels loses (write_exr without full_float): values beyond
// +-65504, which are clamped, and non-zero values below half's smallest step (2^-24; anything
// under half of it rounds to 0), which become 0. Counted over every value of every colour layer;
// data layers are left out (a miss's depth is clamped to 65504 on purpose: docs/layers.md).
struct HalfRangeLoss {
  size_t values = 0;          // all values of all layers
  size_t nonzero = 0;         // of which not 0
  size_t clamped = 0;         // |v| > 65504
  size_t flushed_to_zero = 0; // 0 < |v| < 2^-25
};
HalfRangeLoss half_range_loss(const FrameImage& image);

// Reads every layer of the file's first part. Channels are grouped by the text before their
// last '.'; R, G, B without a prefix form the combined layer "", which comes first in layers;
// other layers follow in channel-list (alphabetical) order. A group's other channels (A, Z,
// N.X, ...) form its data layer in data_layers ("" for bare ones such as Z), channels in the
// file's (alphabetical) order, full_float when all of them are stored as float; subsampled ones
// are skipped. Every string attribute of the header is returned, including
// standard ones such as "owner" when present. Values are returned as read; no finiteness check.
// A missing or unreadable file, a non-EXR file, an image wider or taller than 16384, a layer lacking one of R, G, B, or a file with no
// RGB layer at all is a pm::InputError naming the file.
FrameImage read_exr(const std::string& path);

// The header attribute that marks a checkpoint: the image of a frame whose passes are not all
// done yet (render --checkpoint-every; docs/progressive.md).
extern const char* const kCheckpointAttribute;

// What check_exr_file found: complete, absent, cut short (a file that starts as an EXR but whose
// header or scanline chunks do not all read), or unreadable (not a regular file, no read
// permission, not an EXR at all), or a checkpoint of a frame still being rendered (a readable
// image, kCheckpointAttribute set: render --resume continues it).
enum class ExrFileState { complete, missing, truncated, unreadable, checkpoint };

struct ExrFileCheck {
  ExrFileState state = ExrFileState::missing;
  std::string problem;     // why it is not complete, for messages; empty when complete
  int width = 0, height = 0;  // the data window, when the header could be read
};

// Opens the file as an EXR and decodes the pixels of one channel, so every scanline chunk is read:
// about the cost of one image read. Never throws.
ExrFileCheck check_exr_file(const std::string& path);

// check_exr_file(path).state == complete: the file was written to the end and is no checkpoint
// (used by --resume to skip finished frames).
bool exr_is_complete(const std::string& path);

// "complete", "missing", "truncated" or "unreadable".
const char* exr_file_state_name(ExrFileState state);

}  // namespace pm
