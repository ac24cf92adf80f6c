// `pmrender render [SCENE]`: loads the scene (or the built-in Cornell box), selects frames
// (--frames, --frame, or the scene's whole sequence) and checks everything the run needs before
// any device work: the output and preview paths (output_checks.h), the camera at every frame and
// the host memory of a frame (memory.h). --resume skips frames whose file is complete. It then
// opens the devices once (frame_devices.h), makes one frame job per device group (one Renderer:
// scene BVH built once, photons reused over camera-only motion; under --method auto the race's
// winner, render/method_race.h), hands the frames to the frame loop (frame_loop.h: claims,
// rendering, writing, failures, signals) and prints the run's summary. A frame that fails is
// reported and the others still render; the exit code is then 1 (docs/animation.md, "Batch
// rendering").
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include "cli/commands.h"
#include "cli/concurrent_writers.h"
#include "cli/frame_devices.h"
#include "cli/frame_job.h"
#include "cli/frame_loop.h"
#include "cli/memory.h"
#include "cli/number_parsing.h"
#include "cli/output_checks.h"
#include "cli/progress_line.h"
#include "cli/render_options.h"
#include "cli/scene_beside_driver.h"
#include "cli/signals.h"
#include "cli/startup_report.h"
#include "render/device.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/frame_claim.h"
#include "render/interruption.h"
#include "render/method_race.h"
#include "render/output_pattern.h"
#include "render/preview_exposure.h"
#include "render/renderer.h"
#include "render/scene_frame.h"
#include "scene_io/frame_spec.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

namespace {

// Largest frame number --frames can name (frame_spec.cpp reads at most 9 digits).
const int kMaxFrameNumber = 999999999;
// The pass cap of a --time or --target-error budget given without --passes.
const uint32_t kBudgetPassCap = 1000000;

struct RenderCommandOptions {
  RenderOptions render;
  std::string output;
  bool full_float = false;
  std::string layers;  // --layers: extra layers (render/film_layers.h), checked while parsing
  std::string preview;
  double exposure_ev = 0;
  CLI::Option* exposure_option = nullptr;
  int frame = 0;
  std::string frames;
  bool resume = false;
  bool quiet = false;
  bool verbose = false;
  double seconds = 0;
  double target_error = 0;
  std::string devices;
  uint32_t checkpoint_every = 0;
  ClaimRules claims;
  bool wait_for_claimed = false;
  CLI::Option* frame_option = nullptr;
  CLI::Option* frames_option = nullptr;
};

// --layers: each name known, before anything is loaded (parse_film_layers says what is wrong).
CLI::Validator film_layer_list() {
  return CLI::Validator(
      [](std::string& text) {
        try {
          parse_film_layers(text);
          return std::string();
        } catch (const SettingError& e) {
          return std::string(e.what()).substr(e.setting().size() + 2);  // CLI11 puts the option's name first
        }
      },
      "", "film_layer_list");
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
  if (frames_given) return parse_frames_option(o.frames, first, last);
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

// The output pattern and the preview's name each frame for themselves, and the camera is usable
// at every frame.
void check_frames(const RenderCommandOptions& o, const Scene& scene, const std::string& pattern,
                  const std::vector<int>& frames) {
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
}

FrameJobOptions frame_job_options(const RenderCommandOptions& o, const RenderSettings& settings) {
  FrameJobOptions job_options;
  job_options.budget.max_passes = settings.passes;
  job_options.budget.seconds = o.seconds;
  job_options.budget.target_error = o.target_error;
  job_options.budget.checkpoint_every = o.checkpoint_every;
  // A budget with no --passes of its own runs until the budget stops it.
  if (job_options.budget.open_ended() && o.render.passes_option->count() == 0) job_options.budget.max_passes = kBudgetPassCap;
  job_options.full_float = o.full_float;
  job_options.resume = o.resume;
  job_options.quiet = o.quiet;
  job_options.verbose = o.verbose && !o.quiet;
  if (o.exposure_option->count() > 0) job_options.preview_exposure_ev = o.exposure_ev;
  return job_options;
}

// --method auto: the methods race on the first frame; the winner renders every frame, the first
// going on from its passes in the race (render/method_race.h).
void race_and_make_jobs(const RenderCommandOptions& o, const Scene& scene, RenderSettings& settings,
                        const FrameJobOptions& job_options, const std::vector<int>& todo, int width, int height,
                        FrameDevices& opened) {
  const std::vector<RaceCandidate> candidates = method_candidates(o.render);
  MethodChoice race = race_methods(*opened.devices.front(), scene, settings, candidates, todo.front(), job_options.budget);
  settings.method = candidates[race.winner].method;
  make_frame_jobs(opened, todo.size() > 1, scene, settings, job_options, width, height, std::move(race.renderer));
  opened.jobs.front()->continue_from(todo.front(), std::move(race.sums), race.race_seconds);
  for (auto& job : opened.jobs)
    job->add_attributes({{"pmrender/method_choice", candidates[race.winner].label}, {"pmrender/method_race", race.summary()}});
  if (o.quiet) return;
  if (o.verbose)
    for (const std::string& line : race.rounds) std::printf("method auto: %s\n", line.c_str());
  std::printf("method auto: %s, raced on frame %d in %s (%s)\n", candidates[race.winner].label.c_str(), todo.front(),
              seconds_text(race.race_seconds).c_str(), race.summary().c_str());
  std::fflush(stdout);
}

// A sequence's summary line: "rendered 21 of 24 frames in 9.1 s (434 ms/frame), ...".
void print_sequence_summary(const FrameTallies& t, size_t selected, size_t todo, size_t skipped, size_t jobs,
                            double seconds) {
  std::printf("rendered %zu of %zu frames in %s", t.rendered, selected, seconds_text(seconds).c_str());
  if (t.rendered > 0) std::printf(" (%s/frame)", seconds_text(seconds / double(todo)).c_str());
  if (t.reused > 0) std::printf(", photons reused in %zu", t.reused);
  if (skipped > 0 || t.finished_elsewhere > 0) std::printf(", %zu already complete", skipped + t.finished_elsewhere);
  if (!t.held_elsewhere.empty()) std::printf(", %zu being rendered by other processes", t.held_elsewhere.size());
  if (!t.failed.empty()) std::printf(", %zu failed", t.failed.size());
  if (jobs > 1) {
    std::printf(", frames per device:");
    for (size_t j = 0; j < jobs; ++j) std::printf("%s %zu", j ? "," : "", t.frames_per_job[j]);
  }
  std::printf("\n");
}

int run_render(const RenderCommandOptions& o) {
  StartupSteps startup;
  if (o.exposure_option->count() > 0 && o.preview.empty())
    throw InputError("--exposure: sets the exposure of the --preview PNG; give --preview NAME.png too");
  startup.mark("options");
  SceneLoadReport report;
  Scene scene = load_scene_beside_driver(o.render, o.devices.empty() ? o.render.device : -1, &report, &startup);
  RenderSettings settings = render_settings(o.render, o.seconds > 0 || o.target_error > 0);
  settings.layers = parse_film_layers(o.layers);
  const std::string pattern = o.output.empty() ? default_output_pattern(scene.name) : o.output;
  const std::vector<int> frames = select_frames(o, scene);
  check_frames(o, scene, pattern, frames);

  std::vector<int> todo, skipped;
  for (int f : frames) {
    // A checkpoint image is not complete (exr_is_complete): its frame continues.
    if (o.resume && exr_is_complete(expand_output_pattern(pattern, f))) skipped.push_back(f);
    else todo.push_back(f);
  }
  if (o.verbose)
    for (int f : skipped) std::printf("skipped %s (complete)\n", expand_output_pattern(pattern, f).c_str());

  // Every output target and the host memory of a frame, before any device work.
  std::vector<std::string> targets, previews;
  for (int f : todo) {
    targets.push_back(expand_output_pattern(pattern, f));
    if (!o.preview.empty()) previews.push_back(expand_output_pattern(o.preview, f));
  }
  check_output_paths("-o", targets, ".exr");
  check_output_paths("--preview", previews, ".png");
  const int width = settings.width > 0 ? settings.width : scene.camera.width;
  const int height = settings.height > 0 ? settings.height : scene.camera.height;
  if (!todo.empty()) check_host_memory_for_frame(width, height, !settings.layers.empty());
  const FrameJobOptions job_options = frame_job_options(o, settings);

  // Devices, their renderers and the frame jobs (frame_devices.h), once the input is known good.
  const std::vector<int> device_list = parse_device_list(o.devices);
  startup.mark("frames and output checks");
  FrameDevices opened;
  if (!todo.empty()) {
    DeviceChoice choice{o.render.backend, o.render.device, !o.devices.empty(), device_list};
    opened = open_devices(choice, todo.size() > 1, o.checkpoint_every);
    print_device_startup_messages(device_pointers(opened), o.verbose, o.quiet);
    remove_stale_temporaries(targets, o.verbose);
    if (o.render.method == kAutoMethod) race_and_make_jobs(o, scene, settings, job_options, todo, width, height, opened);
    else make_frame_jobs(opened, todo.size() > 1, scene, settings, job_options, width, height);
  }
  remove_stale_claims_of_complete_frames(pattern, skipped, o.claims, o.verbose);
  // Input is valid from here on: say what loading tolerated, then render.
  if (!o.quiet)
    for (const std::string& warning : report.warnings) std::fprintf(stderr, "pmrender: warning: %s\n", warning.c_str());

  FrameLoopOptions loop_options;
  loop_options.pattern = pattern;
  loop_options.preview = o.preview;
  loop_options.claims = o.claims;
  loop_options.budget = job_options.budget;
  loop_options.selected_frames = frames.size();
  loop_options.resume = o.resume;
  loop_options.wait_for_claimed = o.wait_for_claimed;
  loop_options.full_float = o.full_float;
  loop_options.quiet = o.quiet;
  loop_options.verbose = o.verbose;
  FrameLoop loop(loop_options, opened.jobs, opened.devices.empty() ? nullptr : opened.devices.front().get());
  loop.run(todo);
  loop.clear_progress();
  const FrameTallies& tallies = loop.tallies();
  if (interruption_signal() != 0) return report_interruption(tallies.rendered, todo.size());

  if (frames.size() > 1 && !o.quiet)
    print_sequence_summary(tallies, frames.size(), todo.size(), skipped.size(), opened.jobs.size(), loop.seconds());
  if (o.verbose && !opened.devices.empty()) {
    StartupReport startup_report = make_startup_report(startup, device_pointers(opened), renderer_pointers(opened));
    startup_report.first_frame_wall_ms = tallies.first_frame_ms;
    print_startup_report(stdout, startup_report, -1, "");
    print_memory_summary(tallies.first_frame_memory, *opened.devices.front());
  }
  if (!tallies.failed.empty()) {
    std::fprintf(stderr, "pmrender: %zu of %zu frames failed: %s\n", tallies.failed.size(), frames.size(),
                 frame_list(tallies.failed).c_str());
    return 1;
  }
  return 0;
}

}  // namespace

Run add_render_command(CLI::App& app) {
  auto options = std::make_shared<RenderCommandOptions>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene or a sequence of its frames to OpenEXR "
                                               "(default: the built-in Cornell box)");
  add_render_options(cmd, options->render);
  cmd->add_option("-o,--output", options->output, "Output pattern; runs of # are the zero-padded frame number")
      ->default_str("out/<scene>_####.exr");
  cmd->add_flag("--float", options->full_float, "Write 32-bit float channels instead of half");
  cmd->add_option("--layers", options->layers,
                  "Extra EXR layers for compositing and denoising, a comma list of albedo, normal, depth, position, "
                  "object_id, material_id, or all (docs/layers.md); default: none")
      ->check(film_layer_list());
  cmd->add_option("--preview", options->preview, "Also write a tone-mapped 8-bit PNG of the combined layer here (# as in -o)");
  options->exposure_option =
      cmd->add_option("--exposure", options->exposure_ev,
                      "Exposure of the --preview PNG in stops (radiance times 2^EV), -32 to 32; default: automatic, "
                      "the 99th percentile of each frame's luminance as white")
          ->transform(finite_in(-kMaxExposureStops, kMaxExposureStops));
  options->frames_option =
      cmd->add_option("--frames", options->frames,
                      "Frames to render, e.g. 1-30,47,100-200:2 (default: the scene's whole sequence)");
  options->frame_option =
      cmd->add_option("--frame", options->frame, "One frame to render (the same as --frames N)")->transform(integer_in(0, kMaxFrameNumber));
  cmd->add_flag("--resume", options->resume,
                "Skip frames whose output file is already complete; continue checkpointed frames from their checkpoint");
  cmd->add_option("--time", options->seconds,
                  "Per frame: stop after the pass that reaches this many seconds (--passes, if given, stays a cap)")
      ->transform(non_negative_float());
  cmd->add_option("--target-error", options->target_error,
                  "Per frame: stop when the estimated relative error of the indirect light falls to this, e.g. 0.01 "
                  "(from 4 passes on; docs/progressive.md)")
      ->transform(finite_in(0, 1));
  cmd->add_option("--devices", options->devices,
                  "Render on several devices of the backend: 'all' or indices like 0,1. A sequence's frames are "
                  "shared out; a single frame's passes are");
  cmd->add_option("--checkpoint-every", options->checkpoint_every,
                  "Write the frame so far every N passes (a normal EXR plus <file>.pmstate); --resume continues it")
      ->transform(any_unsigned32());
  add_stale_claim_option(cmd, options->claims);
  cmd->add_flag("--wait-for-claimed-frames", options->wait_for_claimed,
                "Frames another process has claimed: wait until they are complete, and render any whose claim is "
                "released without a file or goes stale (docs/farm.md, \"Frame claims\")");
  cmd->add_flag("-q,--quiet", options->quiet, "Print nothing on success (no progress, no summary)");
  cmd->add_flag("-v,--verbose", options->verbose,
                "Also list skipped frames and removed stale temporaries and claims, and print host and device memory "
                "at the end");
  return [options] { return run_render(*options); };
}

}  // namespace pm::cli
