// `pmrender render [SCENE]`: loads the scene (or the built-in Cornell box), selects frames
// (--frames, --frame, or the scene's whole sequence), opens the devices once (frame_devices.h) and
// renders the frames with one Renderer per device (scene BVH built once, photons reused over
// camera-only motion), writing each as OpenEXR (temporary name, then rename) on a writing thread
// while the device renders the next frame. --resume skips frames whose file is complete. Each
// frame is claimed first (render/frame_claim.h): a frame another live process is rendering is
// skipped, or waited for with --wait-for-claimed-frames. A frame that fails is reported and the
// others still render; the exit code is then 1 (docs/animation.md, "Batch rendering"). Output
// paths and memory are checked before the device opens (output_checks.h, memory.h); SIGINT and
// SIGTERM stop between frames (signals.h).
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>
#include <mutex>
#include <thread>

#include "cli/commands.h"
#include "cli/concurrent_writers.h"
#include "cli/frame_devices.h"
#include "cli/frame_job.h"
#include "cli/frame_warnings.h"
#include "cli/memory.h"
#include "cli/number_parsing.h"
#include "cli/output_checks.h"
#include "cli/progress_line.h"
#include "cli/signals.h"
#include "cli/render_options.h"
#include "cli/scene_beside_driver.h"
#include "cli/startup_report.h"
#include "render/background_writer.h"
#include "render/device.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/frame_claim.h"
#include "render/frame_runs.h"
#include "render/interruption.h"
#include "render/method_race.h"
#include "render/output_pattern.h"
#include "render/preview_exposure.h"
#include "render/preview_png.h"
#include "render/renderer.h"
#include "render/scene_frame.h"
#include "scene_io/cornell_box.h"
#include "scene_io/frame_spec.h"
#include "scene_io/scene_file.h"

namespace pm::cli {

namespace {

// Largest frame number --frames can name (frame_spec.cpp reads at most 9 digits).
const int kMaxFrameNumber = 999999999;
// The pass cap of a --time or --target-error budget given without --passes.
const uint32_t kBudgetPassCap = 1000000;
// How often --wait-for-claimed-frames looks at the claims of other processes again.
const double kClaimPollSeconds = 1.0;

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

  // Devices, their renderers and the frame jobs (frame_devices.h), once the input is known good.
  const std::vector<int> device_list = parse_device_list(o.devices);
  startup.mark("frames and output checks");
  FrameDevices opened;
  if (!todo.empty()) {
    DeviceChoice choice{o.render.backend, o.render.device, !o.devices.empty(), device_list};
    opened = open_devices(choice, todo.size() > 1, o.checkpoint_every);
    print_device_startup_messages(device_pointers(opened), o.verbose, o.quiet);
    remove_stale_temporaries(targets, o.verbose);
    if (o.render.method == kAutoMethod) {
      // The methods race on the first frame; the winner renders every frame, the first going on
      // from its passes in the race (render/method_race.h).
      const std::vector<RaceCandidate> candidates = method_candidates(o.render);
      MethodChoice race =
          race_methods(*opened.devices.front(), scene, settings, candidates, todo.front(), job_options.budget);
      settings.method = candidates[race.winner].method;
      make_frame_jobs(opened, todo.size() > 1, scene, settings, job_options, width, height, std::move(race.renderer));
      opened.jobs.front()->continue_from(todo.front(), std::move(race.sums), race.race_seconds);
      for (auto& job : opened.jobs)
        job->add_attributes({{"pmrender/method_choice", candidates[race.winner].label},
                             {"pmrender/method_race", race.summary()}});
      if (!o.quiet) {
        if (o.verbose)
          for (const std::string& line : race.rounds) std::printf("method auto: %s\n", line.c_str());
        std::printf("method auto: %s, raced on frame %d in %s (%s)\n", candidates[race.winner].label.c_str(),
                    todo.front(), seconds_text(race.race_seconds).c_str(), race.summary().c_str());
        std::fflush(stdout);
      }
    } else {
      make_frame_jobs(opened, todo.size() > 1, scene, settings, job_options, width, height);
    }
  }
  std::vector<std::unique_ptr<Device>>& devices = opened.devices;
  double first_frame_ms = -1;
  std::vector<std::unique_ptr<FrameJob>>& jobs = opened.jobs;
  remove_stale_claims_of_complete_frames(pattern, skipped, o.claims, o.verbose);
  // Input is valid from here on: say what loading tolerated, then render.
  if (!o.quiet)
    for (const std::string& warning : report.warnings) std::fprintf(stderr, "pmrender: warning: %s\n", warning.c_str());

  const bool sequence = frames.size() > 1;
  ProgressLine progress(!o.quiet);
  std::mutex output;  // progress, messages and the counts below, across device threads
  FrameWarnings warnings(o.full_float);
  for (auto& job : jobs)
    job->set_image_check([&](int f, const FrameImage& image, int repaired) {
      const HalfRangeLoss loss = warnings.measure(image);  // before the lock: devices write frames at once
      std::lock_guard<std::mutex> lock(output);
      progress.clear();
      warnings.report(f, loss, repaired);
    });
  MemorySnapshot first_frame_memory;
  std::vector<int> failed, held_elsewhere;  // held: another live process has claimed the frame
  size_t rendered = 0, reused = 0, done = 0, finished_elsewhere = 0;
  const auto start = std::chrono::steady_clock::now();
  install_interrupt_handlers();
  ClaimRefresher claim_refresher;
  // The "wrote" line of a frame this process rendered; called with output locked.
  std::vector<size_t> frames_per_job(jobs.size(), 0);
  auto report_written = [&](const FrameJob& job, int f, const std::string& path, const FrameOutcome& outcome) {
    if (++rendered == 1) {
      first_frame_memory = {host_rss_bytes(), devices.front()->allocated_bytes()};
      first_frame_ms = outcome.render_ms;
    }
    for (size_t j = 0; j < jobs.size(); ++j) frames_per_job[j] += jobs[j].get() == &job ? 1 : 0;
    reused += outcome.photons_reused ? 1 : 0;
    if (!o.quiet) {
      std::printf("wrote %s (frame %d, %dx%d, %s, %.2f ms", path.c_str(), f, job.width(), job.height(),
                  job.devices().c_str(), outcome.render_ms);
      if (outcome.result.passes > 1 || job_options.budget.open_ended())
        std::printf(", %u passes (%s)", outcome.result.passes, outcome.result.stopped_by.c_str());
      if (outcome.result.error >= 0) std::printf(", error ~%.2f%%", 100.0 * outcome.result.error);
      if (outcome.resumed) std::printf(", continued from its checkpoint");
      if (outcome.photons_reused) std::printf(", photons reused");
      std::printf(")\n");
      std::fflush(stdout);
    }
    if (outcome.result.stopped_by == "levelled")
      std::fprintf(stderr,
                   "pmrender: warning: frame %d: the error estimate levelled off at %.2f%%, above the target %.2f%%: "
                   "more passes of this method do not lower it (docs/progressive.md)\n",
                   f, 100.0 * outcome.result.error, 100.0 * job_options.budget.target_error);
  };
  // A frame this process claimed and rendered, waiting for its file.
  struct PendingFrame {
    FrameJob* job = nullptr;
    RenderedFrame rendered;
    FrameClaim claim;
  };
  auto count_done = [&](int f) {
    std::lock_guard<std::mutex> lock(output);
    progress.show_count("frame " + std::to_string(f), ++done, todo.size(),
                        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), "frame");
  };
  // Whether a failure of frame f is reported here (the others go on) or thrown to main().
  auto report_failure = [&](int f, const std::exception& e) {
    if (todo.size() == 1 && frames.size() == 1) throw;  // a single frame: main() reports it as before
    std::lock_guard<std::mutex> lock(output);
    progress.clear();
    std::fprintf(stderr, "pmrender: frame %d: %s\n", f, e.what());
    failed.push_back(f);
  };
  // Claims frame f and renders it; returns the frame to write, or nothing where it was not rendered
  // here. waited: f was held by another process before (and said so), so a complete file now is
  // that process's work, with or without --resume.
  auto render_frame = [&](FrameJob& job, int f, bool waited) -> std::shared_ptr<PendingFrame> {
    const std::string path = expand_output_pattern(pattern, f);
    try {
      ClaimAttempt attempt = claim_frame(path, o.claims);
      std::unique_lock<std::mutex> lock(output);
      progress.clear();
      if (!attempt.claim.held()) {
        held_elsewhere.push_back(f);
        if (!waited && !o.quiet)
          std::printf("skipped %s (being rendered by %s)\n", path.c_str(), claim_holder_text(*attempt.other).c_str());
        std::fflush(stdout);
        return nullptr;  // counted once it is done, here or there
      }
      if (attempt.other && !o.quiet)
        std::printf("took over the stale claim %s: %s\n", attempt.other->path.c_str(), attempt.other->why_stale.c_str());
      std::fflush(stdout);
      lock.unlock();
      // Another process may have finished the frame since the --resume scan, or while this one waited.
      if ((o.resume || waited) && exr_is_complete(path)) {
        lock.lock();
        ++finished_elsewhere;
        if (o.verbose) std::printf("skipped %s (complete)\n", path.c_str());
      } else {
        auto pending = std::make_shared<PendingFrame>();
        pending->job = &job;
        pending->rendered = job.render(f, path, o.preview.empty() ? "" : expand_output_pattern(o.preview, f), progress);
        pending->claim = std::move(attempt.claim);
        return pending;
      }
    } catch (const Interrupted&) {
      return nullptr;  // the frame in progress is abandoned (its checkpoint, if any, stays)
    } catch (const std::bad_alloc&) {
      throw;  // not this frame's fault: main() reports it and the run ends
    } catch (const std::exception& e) {
      report_failure(f, e);
    }
    count_done(f);
    return nullptr;
  };
  // Writes a rendered frame's file, then releases its claim (the file is in place).
  auto write_frame = [&](PendingFrame& pending) {
    const int f = pending.rendered.frame;
    try {
      pending.job->write(pending.rendered);
      pending.claim.release();
      std::lock_guard<std::mutex> lock(output);
      progress.clear();
      report_written(*pending.job, f, pending.rendered.path, pending.rendered.outcome);
    } catch (const Interrupted&) {
      return;  // no partial file is left (atomic_file.h); the claim goes with `pending`
    } catch (const std::bad_alloc&) {
      throw;
    } catch (const std::exception& e) {
      report_failure(f, e);
    }
    count_done(f);
  };
  // The frames next_frame() hands out, on one job: each frame's file is written on the job's writing
  // thread while the job's devices render the next frame (at most one frame waits per job). A
  // single frame is written at once.
  auto render_frames = [&](FrameJob& job, const std::function<std::optional<int>()>& next_frame) {
    BackgroundWriter writer;
    while (interruption_signal() == 0) {
      const std::optional<int> f = next_frame();
      if (!f) break;
      std::shared_ptr<PendingFrame> pending = render_frame(job, *f, false);
      writer.wait();
      if (!pending) continue;
      if (todo.size() == 1) write_frame(*pending);
      else writer.submit([&write_frame, pending] { write_frame(*pending); });
    }
    writer.wait();
  };
  if (jobs.size() <= 1) {
    if (!jobs.empty()) {
      jobs.front()->set_pass_progress(&output);  // one frame at a time: its passes may show
      size_t i = 0;
      render_frames(*jobs.front(), [&]() -> std::optional<int> {
        if (i < todo.size()) return todo[i++];
        return std::nullopt;
      });
    }
  } else {
    // One thread per device, each on its own contiguous run of frames, taking over half of the
    // longest run left when its own is done (render/frame_runs.h).
    FrameRuns runs(todo.size(), jobs.size());
    std::vector<std::thread> threads;
    std::exception_ptr failure;
    for (size_t d = 0; d < jobs.size(); ++d)
      threads.emplace_back([&, d] {
        try {
          render_frames(*jobs[d], [&]() -> std::optional<int> {
            if (std::optional<size_t> i = runs.next(d)) return todo[*i];
            return std::nullopt;
          });
        } catch (...) {
          std::lock_guard<std::mutex> lock(output);
          if (!failure) failure = std::current_exception();
        }
      });
    for (std::thread& t : threads) t.join();
    if (failure) std::rethrow_exception(failure);
    std::sort(failed.begin(), failed.end());
  }
  // --wait-for-claimed-frames: the frames other processes held, until each is complete, here (its
  // claim was released without a file, or went stale) or there.
  if (o.wait_for_claimed && !held_elsewhere.empty() && !o.quiet) {
    progress.clear();
    std::printf("waiting for %zu frame%s other processes are rendering: %s\n", held_elsewhere.size(),
                held_elsewhere.size() == 1 ? "" : "s", frame_list(held_elsewhere).c_str());
    std::fflush(stdout);
  }
  while (o.wait_for_claimed && !held_elsewhere.empty() && interruption_signal() == 0) {
    sleep_unless_interrupted(kClaimPollSeconds);
    std::vector<int> waiting;
    waiting.swap(held_elsewhere);
    std::sort(waiting.begin(), waiting.end());
    for (size_t i = 0; i < waiting.size() && interruption_signal() == 0; ++i)
      if (std::shared_ptr<PendingFrame> pending = render_frame(*jobs.front(), waiting[i], true)) write_frame(*pending);
  }
  progress.clear();
  if (interruption_signal() != 0) return report_interruption(rendered, todo.size());
  const double total_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  if (sequence && !o.quiet) {
    std::printf("rendered %zu of %zu frames in %s", rendered, frames.size(), seconds_text(total_seconds).c_str());
    if (rendered > 0) std::printf(" (%s/frame)", seconds_text(total_seconds / double(todo.size())).c_str());
    if (reused > 0) std::printf(", photons reused in %zu", reused);
    if (!skipped.empty() || finished_elsewhere > 0)
      std::printf(", %zu already complete", skipped.size() + finished_elsewhere);
    if (!held_elsewhere.empty()) std::printf(", %zu being rendered by other processes", held_elsewhere.size());
    if (!failed.empty()) std::printf(", %zu failed", failed.size());
    if (jobs.size() > 1) {
      std::printf(", frames per device:");
      for (size_t j = 0; j < jobs.size(); ++j) std::printf("%s %zu", j ? "," : "", frames_per_job[j]);
    }
    std::printf("\n");
  }
  if (o.verbose && !devices.empty()) {
    StartupReport startup_report = make_startup_report(startup, device_pointers(opened), renderer_pointers(opened));
    startup_report.first_frame_wall_ms = first_frame_ms;
    print_startup_report(stdout, startup_report, -1, "");
    print_memory_summary(first_frame_memory, *devices.front());
  }
  if (!failed.empty()) {
    std::fprintf(stderr, "pmrender: %zu of %zu frames failed: %s\n", failed.size(), frames.size(),
                 frame_list(failed).c_str());
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
