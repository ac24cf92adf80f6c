// `pmrender frames check -o PATTERN --frames SPEC [--resolution WxH]`: whether a rendered sequence
// is all there. Lists every frame whose file is missing, truncated, unreadable or of the wrong
// size, one line each with the reason, then a summary; a frame that is not complete but claimed
// (render/frame_claim.h) is "being rendered" or, when its claim is stale, "stale claim". Exit
// codes: 0 every frame complete, 1 any frame not, 2 bad usage; so a pipeline (and the farm
// script's last step) can gate on it.
#include <cstdio>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/concurrent_writers.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/frame_claim.h"
#include "render/output_pattern.h"
#include "scene_io/frame_spec.h"

namespace pm::cli {

namespace {

// The largest frame number a specification can name (frame_spec.cpp reads at most 9 digits).
constexpr int kLastFrameNumber = 999999999;

struct FramesCheckOptions {
  std::string output;
  std::string frames;
  std::string resolution;
  ClaimRules claims;
  bool quiet = false;
};

int run_frames_check(const FramesCheckOptions& o) {
  const std::vector<int> frames = parse_frames_option(o.frames, 0, kLastFrameNumber);
  if (frames.size() > 1 && !pattern_has_frame_field(o.output))
    throw InputError("-o: '" + o.output + "' has no # for the frame number, but " + std::to_string(frames.size()) +
                     " frames are selected");
  int width = 0, height = 0;
  if (!o.resolution.empty()) parse_resolution(o.resolution, &width, &height);

  std::map<std::string, size_t> bad_counts;  // reason -> frames
  for (int f : frames) {
    const std::string path = expand_output_pattern(o.output, f);
    const ExrFileCheck check = check_exr_file(path);
    std::string reason, detail = check.problem;
    if (check.state != ExrFileState::complete) {
      reason = exr_file_state_name(check.state);
    } else if (width > 0 && (check.width != width || check.height != height)) {
      reason = "wrong size";
      detail = std::to_string(check.width) + "x" + std::to_string(check.height) + ", expected " + o.resolution;
    }
    if (reason.empty()) continue;
    // Not complete, but claimed: say so first, the file's state after it.
    if (const std::optional<ClaimInspection> claim = inspect_claim(claim_path_for(path), o.claims)) {
      detail = reason + ", " + detail + "; ";
      if (claim->stale) {
        reason = "stale claim";
        detail += claim->why_stale;
      } else {
        reason = "being rendered";
        detail += "claimed by " + claim_holder_text(*claim);
      }
    }
    ++bad_counts[reason];
    std::printf("frame %d: %s: %s (%s)\n", f, path.c_str(), reason.c_str(), detail.c_str());
  }

  size_t bad = 0;
  std::string summary;
  for (const auto& [reason, count] : bad_counts) {
    bad += count;
    summary += ", " + std::to_string(count) + " " + reason;
  }
  if (!o.quiet || bad > 0)
    std::printf("%zu frame%s: %zu complete%s\n", frames.size(), frames.size() == 1 ? "" : "s", frames.size() - bad,
                summary.c_str());
  return bad == 0 ? 0 : 1;
}

}  // namespace

Run add_frames_command(CLI::App& app) {
  auto options = std::make_shared<FramesCheckOptions>();
  CLI::App* frames = app.add_subcommand("frames", "Work with the files of a rendered sequence");
  frames->require_subcommand(1);
  CLI::App* check = frames->add_subcommand(
      "check", "List frames whose file is missing, truncated, unreadable or of the wrong size, and whether another "
               "process is rendering them (exit 1 if any)");
  check->add_option("-o,--output", options->output, "Output pattern the frames were written with (# = frame number)")
      ->required();
  check->add_option("--frames", options->frames, "Frames to check, e.g. 0-99 or 1-30,47,100-200:2")->required();
  check->add_option("--resolution", options->resolution, "WIDTHxHEIGHT every frame must have");
  add_stale_claim_option(check, options->claims);
  check->add_flag("-q,--quiet", options->quiet, "Print only the frames that are not complete");
  return [options] { return run_frames_check(*options); };
}

}  // namespace pm::cli
