// `pmrender render [SCENE]`: loads the scene (or the built-in Cornell box), selects frames
// (--frames, --frame, or the scene's whole sequence), opens the device once and renders the frames
// with one Renderer (scene BVH built once, photons reused over camera-only motion), writing each
// as OpenEXR (temporary name, then rename). --resume skips frames whose file is complete. A frame
// that fails is reported and the others still render; the exit code is then 1
// (docs/animation.md, "Batch rendering"). Output paths and memory are checked before the device
// opens (output_checks.h, memory.h); SIGINT/SIGTERM stop between frames (signals.h).
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <set>

#include "animations/frame_spec.h"
#include "animations/scene_animation.h"
#include "cli/commands.h"
#include "cli/frame_warnings.h"
#include "cli/memory.h"
#include "cli/number_parsing.h"
#include "cli/output_checks.h"
#include "cli/signals.h"
#include "cli/render_options.h"
#include "render/device.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/interruption.h"
#include "render/output_pattern.h"
#include "render/preview_png.h"
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

namespace {

namespace fs = std::filesystem;

// Largest frame number --frames can name (frame_spec.cpp reads at most 9 digits).
const int kMaxFrameNumber = 999999999;

struct RenderCommandOptions {
  RenderOptions render;
  std::string output;
  bool full_float = false;
  std::string preview;
  int frame = 0;
  std::string frames;
  bool resume = false;
  bool quiet = false;
  bool verbose = false;
  std::string photon_sequence = "random";
  bool no_photon_reuse = false;
  CLI::Option* frame_option = nullptr;
  CLI::Option* frames_option = nullptr;
};

std::string seconds_text(double s) {
  char text[32];
  if (s < 1) {
    std::snprintf(text, sizeof(text), "%.0f ms", s * 1000);
  } else if (s < 60) {
    std::snprintf(text, sizeof(text), "%.1f s", s);
  } else {
    const long total = long(s + 0.5);
    if (total >= 3600)
      std::snprintf(text, sizeof(text), "%ld:%02ld:%02ld", total / 3600, (total / 60) % 60, total % 60);
    else
      std::snprintf(text, sizeof(text), "%ld:%02ld", total / 60, total % 60);
  }
  return text;
}

std::string frame_list(const std::vector<int>& frames) {
  std::string list;
  for (int f : frames) list += (list.empty() ? "" : ", ") + std::to_string(f);
  return list;
}

// The frames to render: --frames, --frame, or else the scene's sequence (frame 0 of a still
// scene). A still scene accepts any frame number (the scene is the same, the random numbers
// differ); a sequence only its own frames.
std::vector<int> select_frames(const RenderCommandOptions& o, const Scene& scene) {
  const SceneAnimation& a = scene.animation;
  const int first = a.enabled ? a.first_frame : 0;
  const int last = a.enabled ? a.last_frame : kMaxFrameNumber;
  const bool frame_given = o.frame_option->count() > 0, frames_given = o.frames_option->count() > 0;
  if (frame_given && frames_given) throw InputError("--frame and --frames: give one of them, not both");
  if (frames_given) return parse_frame_spec(o.frames, first, last);
  if (frame_given) {
    if (o.frame < first || o.frame > last)
      throw InputError("--frame: " + std::to_string(o.frame) + " is outside the scene's frames " + std::to_string(first) +
                       "-" + std::to_string(last));
    return {o.frame};
  }
  std::vector<int> frames;
  for (int f = a.first_frame; f <= a.last_frame; ++f) frames.push_back(f);
  return frames;
}

// Temporaries that write_exr leaves behind when its process is killed mid-write:
// ".<name>.tmp-<pid>-<n>" beside the target. Removes those of the given targets whose process no
// longer exists (each folder is listed once).
void remove_stale_temporaries(const std::vector<std::string>& targets, bool verbose) {
  std::map<fs::path, std::set<std::string>> names_by_folder;
  for (const std::string& target : targets) {
    const fs::path path(target);
    names_by_folder[path.parent_path().empty() ? fs::path(".") : path.parent_path()].insert(path.filename().string());
  }
  for (const auto& [folder, names] : names_by_folder) {
    std::error_code ec;
    if (!fs::is_directory(folder, ec)) continue;
    for (const fs::directory_entry& entry : fs::directory_iterator(folder, ec)) {
      const std::string name = entry.path().filename().string();
      const size_t tmp = name.rfind(".tmp-");
      if (name.size() < 2 || name[0] != '.' || tmp == std::string::npos || !names.count(name.substr(1, tmp - 1))) continue;
      const std::string rest = name.substr(tmp + 5);
      const size_t dash = rest.find('-');
      if (dash == std::string::npos || dash == 0) continue;
      long pid = 0;
      try {
        size_t used = 0;
        pid = std::stol(rest.substr(0, dash), &used);
        if (used != dash) continue;
      } catch (const std::exception&) {
        continue;
      }
      if (pid <= 0 || ::kill(pid_t(pid), 0) == 0 || errno == EPERM) continue;  // its writer is alive
      std::error_code remove_error;
      if (fs::remove(entry.path(), remove_error) && verbose)
        std::printf("removed stale temporary %s\n", entry.path().c_str());
    }
  }
}

class Progress {
 public:
  Progress(bool enabled, size_t total) : enabled_(enabled), total_(total) {}
  void clear() {
    if (enabled_ && drawn_) std::fprintf(stderr, "\r\033[K");
    drawn_ = false;
  }
  void show(int frame, size_t done, double frame_seconds, double mean_seconds) {
    if (!enabled_) return;
    const double percent = total_ ? 100.0 * double(done) / double(total_) : 100.0;
    std::fprintf(stderr, "\r\033[Kframe %d  %zu/%zu (%.0f%%)  %s/frame  ETA %s", frame, done, total_, percent,
                 seconds_text(frame_seconds).c_str(), seconds_text(mean_seconds * double(total_ - done)).c_str());
    std::fflush(stderr);
    drawn_ = true;
  }

 private:
  bool enabled_;
  size_t total_;
  bool drawn_ = false;
};

int run_render(const RenderCommandOptions& o) {
  SceneLoadReport report;
  Scene scene = o.render.scene_path.empty() ? builtin_cornell_box() : load_scene_file(o.render.scene_path, &report);
  RenderSettings settings = render_settings(o.render);
  settings.photons.sequence =
      o.photon_sequence == "halton" ? PM_PHOTON_SEQUENCE_HALTON : PM_PHOTON_SEQUENCE_RANDOM;
  settings.reuse_photons = !o.no_photon_reuse;
  const std::string pattern = o.output.empty() ? default_output_pattern(scene.name) : o.output;

  const std::vector<int> frames = select_frames(o, scene);
  if (frames.size() > 1 && !pattern_has_frame_field(pattern))
    throw InputError("-o: '" + pattern + "' has no # for the frame number, but " + std::to_string(frames.size()) +
                     " frames are selected");
  if (frames.size() > 1 && !o.preview.empty() && !pattern_has_frame_field(o.preview))
    throw InputError("--preview: '" + o.preview + "' has no # for the frame number, but " +
                     std::to_string(frames.size()) + " frames are selected");
  for (int f : frames) {
    const std::string problem = camera_problem(camera_at_frame(scene, f));
    if (!problem.empty()) throw InputError(scene.source + ": camera at frame " + std::to_string(f) + ": " + problem);
  }

  std::vector<int> todo, skipped;
  for (int f : frames) {
    if (o.resume && exr_is_complete(expand_output_pattern(pattern, f))) skipped.push_back(f);
    else todo.push_back(f);
  }
  if (o.verbose)
    for (int f : skipped) std::printf("skipped %s (complete)\n", expand_output_pattern(pattern, f).c_str());

  std::vector<std::string> targets, previews;
  for (int f : todo) {
    targets.push_back(expand_output_pattern(pattern, f));
    if (!o.preview.empty()) previews.push_back(expand_output_pattern(o.preview, f));
  }
  check_output_paths("-o", targets, ".exr");
  check_output_paths("--preview", previews, ".png");
  const int width = settings.width > 0 ? settings.width : scene.camera.width;
  const int height = settings.height > 0 ? settings.height : scene.camera.height;
  if (!todo.empty()) check_host_memory_for_frame(width, height);

  std::unique_ptr<Device> device;
  std::unique_ptr<Renderer> renderer;
  if (!todo.empty()) {
    device = create_device(o.render.backend, o.render.device);
    renderer = std::make_unique<Renderer>(*device, scene, settings);
    check_device_memory(device->allocated_bytes(), device->info(), width, height);  // before PoCL commits it
    remove_stale_temporaries(targets, o.verbose);
  }
  // Input is valid from here on: say what loading tolerated, then render.
  if (!o.quiet)
    for (const std::string& warning : report.warnings) std::fprintf(stderr, "pmrender: warning: %s\n", warning.c_str());

  const bool sequence = frames.size() > 1;
  Progress progress(sequence && !o.quiet && ::isatty(STDERR_FILENO), todo.size());
  std::vector<int> failed;
  size_t rendered = 0, reused = 0;
  const auto start = std::chrono::steady_clock::now();
  FrameWarnings warnings(o.full_float);
  MemorySnapshot first_frame_memory;
  install_interrupt_handlers();
  for (size_t i = 0; i < todo.size() && interruption_signal() == 0; ++i) {
    const int f = todo[i];
    const std::string path = expand_output_pattern(pattern, f);
    const auto frame_start = std::chrono::steady_clock::now();
    try {
      FrameStats stats;
      FrameImage image = renderer->render_frame(f, &stats);
      throw_if_interrupted();  // the frame in progress is abandoned
      progress.clear();
      warnings.check(f, image, stats.repaired_pixels);
      const DeviceInfo& info = device->info();
      image.attributes = {{"pmrender/version", PMRENDER_VERSION},
                          {"pmrender/scene", scene.name + " (" + scene.source + ")"},
                          {"pmrender/frame", std::to_string(f)},
                          {"pmrender/time", std::to_string(frame_time(scene, f))},
                          {"pmrender/photon_frame", std::to_string(stats.photon_frame)},
                          {"pmrender/photons_reused", stats.photons_reused ? "1" : "0"},
                          {"pmrender/backend", info.backend},
                          {"pmrender/device", info.name},
                          {"pmrender/settings", settings.describe()},
                          {"pmrender/render_ms", std::to_string(stats.render_ms)}};
      write_exr(path, image, o.full_float);
      if (!o.preview.empty()) write_preview_png(expand_output_pattern(o.preview, f), image);
      if (++rendered == 1) first_frame_memory = {host_rss_bytes(), device->allocated_bytes()};
      reused += stats.photons_reused;
      if (!o.quiet) {
        std::printf("wrote %s (frame %d, %dx%d, %s: %s, %.2f ms%s)\n", path.c_str(), f, image.width, image.height,
                    info.backend.c_str(), info.name.c_str(), stats.render_ms, stats.photons_reused ? ", photons reused" : "");
        std::fflush(stdout);
      }
    } catch (const Interrupted&) {
      break;
    } catch (const std::bad_alloc&) {
      throw;  // not this frame's fault: main() reports it and the run ends
    } catch (const std::exception& e) {
      if (todo.size() == 1 && frames.size() == 1) throw;  // a single frame: main() reports it as before
      progress.clear();
      std::fprintf(stderr, "pmrender: frame %d: %s\n", f, e.what());
      failed.push_back(f);
    }
    const auto now = std::chrono::steady_clock::now();
    progress.show(f, i + 1, std::chrono::duration<double>(now - frame_start).count(),
                  std::chrono::duration<double>(now - start).count() / double(i + 1));
  }
  progress.clear();
  if (interruption_signal() != 0) return report_interruption(rendered, todo.size());
  const double total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (sequence && !o.quiet) {
    std::printf("rendered %zu of %zu frames in %s", rendered, frames.size(), seconds_text(total_seconds).c_str());
    if (rendered > 0) std::printf(" (%s/frame)", seconds_text(total_seconds / double(todo.size())).c_str());
    if (reused > 0) std::printf(", photons reused in %zu", reused);
    if (!skipped.empty()) std::printf(", %zu already complete", skipped.size());
    if (!failed.empty()) std::printf(", %zu failed", failed.size());
    std::printf("\n");
  }
  if (o.verbose && device) print_memory_summary(first_frame_memory, *device);
  if (!failed.empty()) {
    std::fprintf(stderr, "pmrender: %zu of %zu frames failed: %s\n", failed.size(), frames.size(),
                 frame_list(failed).c_str());
    return 1;
  }
  return 0;
}

}  // namespace

void parse_resolution(const std::string& text, int* width, int* height) {
  const size_t x = text.find_first_of("xX");
  try {
    if (x == std::string::npos) throw InputError("");
    *width = int(parse_unsigned("--resolution", text.substr(0, x), 1, 16384));
    *height = int(parse_unsigned("--resolution", text.substr(x + 1), 1, 16384));
  } catch (const InputError&) {
    throw InputError("--resolution: expected WIDTHxHEIGHT with each a whole number from 1 to 16384, got '" + text +
                     "'");
  }
}

Run add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene or a sequence of its frames to OpenEXR "
                                               "(default: the built-in Cornell box)");
  add_render_options(cmd, options->render);
  cmd->add_option("-o,--output", options->output, "Output pattern; runs of # are the zero-padded frame number")
      ->default_str("out/<scene>_####.exr");
  cmd->add_flag("--float", options->full_float, "Write 32-bit float channels instead of half");
  cmd->add_option("--preview", options->preview, "Also write a tone-mapped 8-bit PNG of the combined layer here (# as in -o)");
  options->frames_option =
      cmd->add_option("--frames", options->frames,
                      "Frames to render, e.g. 1-30,47,100-200:2 (default: the scene's whole sequence)");
  options->frame_option =
      cmd->add_option("--frame", options->frame, "One frame to render (the same as --frames N)")->transform(integer_in(0, kMaxFrameNumber));
  cmd->add_flag("--resume", options->resume, "Skip frames whose output file is already complete");
  cmd->add_option("--photon-sequence", options->photon_sequence,
                  "random, or halton: emission directions from a Halton sequence, the same in every frame")
      ->capture_default_str()
      ->check(CLI::IsMember({"random", "halton"}));
  cmd->add_flag("--no-photon-reuse", options->no_photon_reuse,
                "Trace photons in every frame, keyed by its own frame number, also over camera-only motion");
  cmd->add_flag("-q,--quiet", options->quiet, "Print nothing on success (no progress, no summary)");
  cmd->add_flag("-v,--verbose", options->verbose, "Also list skipped frames and removed stale temporaries, and print host and device memory at the end");
  return [options] { return run_render(*options); };
}

}  // namespace pm::cli
