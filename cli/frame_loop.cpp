// The frame loop of `pmrender render` (frame_loop.h): claims, renders, writes, the frames other
// processes hold, and the tallies of the run.
#include "cli/frame_loop.h"

#include <algorithm>
#include <cstdio>
#include <thread>

#include "cli/concurrent_writers.h"
#include "cli/signals.h"
#include "render/background_writer.h"
#include "render/errors.h"
#include "render/exr_io.h"
#include "render/frame_runs.h"
#include "render/interruption.h"
#include "render/output_pattern.h"

namespace pm::cli {

namespace {

// How often --wait-for-claimed-frames looks at the claims of other processes again.
const double kClaimPollSeconds = 1.0;

}  // namespace

std::string frame_list(const std::vector<int>& frames) {
  std::string list;
  for (int f : frames) list += (list.empty() ? "" : ", ") + std::to_string(f);
  return list;
}

FrameLoop::FrameLoop(const FrameLoopOptions& options, std::vector<std::unique_ptr<FrameJob>>& jobs,
                     const Device* first_device)
    : options_(options), jobs_(jobs), first_device_(first_device), progress_(!options.quiet),
      warnings_(options.full_float) {
  tallies_.frames_per_job.assign(jobs_.size(), 0);
  for (auto& job : jobs_)
    job->set_image_check([this](int f, const FrameImage& image, int repaired) {
      const HalfRangeLoss loss = warnings_.measure(image);  // before the lock: devices write frames at once
      std::lock_guard<std::mutex> lock(output_);
      progress_.clear();
      warnings_.report(f, loss, repaired);
    });
}

void FrameLoop::run(const std::vector<int>& todo) {
  todo_ = todo;
  start_ = std::chrono::steady_clock::now();
  install_interrupt_handlers();
  ClaimRefresher claim_refresher;
  if (jobs_.size() > 1) {
    render_on_every_job();
  } else if (!jobs_.empty()) {
    jobs_.front()->set_pass_progress(&output_);  // one frame at a time: its passes may show
    size_t i = 0;
    render_frames(*jobs_.front(), [&]() -> std::optional<int> {
      if (i < todo_.size()) return todo_[i++];
      return std::nullopt;
    });
  }
  if (options_.wait_for_claimed) wait_for_claimed_frames();
}

void FrameLoop::render_on_every_job() {
  // Each job's thread on its own contiguous run of frames, taking over half of the longest run
  // left when its own is done.
  FrameRuns runs(todo_.size(), jobs_.size());
  std::vector<std::thread> threads;
  std::exception_ptr failure;
  for (size_t d = 0; d < jobs_.size(); ++d)
    threads.emplace_back([&, d] {
      try {
        render_frames(*jobs_[d], [&]() -> std::optional<int> {
          if (std::optional<size_t> i = runs.next(d)) return todo_[*i];
          return std::nullopt;
        });
      } catch (...) {
        std::lock_guard<std::mutex> lock(output_);
        if (!failure) failure = std::current_exception();
      }
    });
  for (std::thread& t : threads) t.join();
  if (failure) std::rethrow_exception(failure);
  std::sort(tallies_.failed.begin(), tallies_.failed.end());
}

void FrameLoop::render_frames(FrameJob& job, const std::function<std::optional<int>()>& next_frame) {
  BackgroundWriter writer;
  while (interruption_signal() == 0) {
    const std::optional<int> f = next_frame();
    if (!f) break;
    std::shared_ptr<PendingFrame> pending = render_frame(job, *f, false);
    writer.wait();
    if (!pending) continue;
    if (todo_.size() == 1) write_frame(*pending);
    else writer.submit([this, pending] { write_frame(*pending); });
  }
  writer.wait();
}

std::shared_ptr<FrameLoop::PendingFrame> FrameLoop::render_frame(FrameJob& job, int f, bool waited) {
  const std::string path = expand_output_pattern(options_.pattern, f);
  try {
    ClaimAttempt attempt = claim_frame(path, options_.claims);
    std::unique_lock<std::mutex> lock(output_);
    progress_.clear();
    if (!attempt.claim.held()) {
      tallies_.held_elsewhere.push_back(f);
      if (!waited && !options_.quiet)
        std::printf("skipped %s (being rendered by %s)\n", path.c_str(), claim_holder_text(*attempt.other).c_str());
      std::fflush(stdout);
      return nullptr;  // counted once it is done, here or there
    }
    if (attempt.other && !options_.quiet)
      std::printf("took over the stale claim %s: %s\n", attempt.other->path.c_str(), attempt.other->why_stale.c_str());
    std::fflush(stdout);
    lock.unlock();
    // Another process may have finished the frame since the --resume scan, or while this one waited.
    if ((options_.resume || waited) && exr_is_complete(path)) {
      lock.lock();
      ++tallies_.finished_elsewhere;
      if (options_.verbose) std::printf("skipped %s (complete)\n", path.c_str());
    } else {
      auto pending = std::make_shared<PendingFrame>();
      pending->job = &job;
      const std::string preview = options_.preview.empty() ? "" : expand_output_pattern(options_.preview, f);
      pending->rendered = job.render(f, path, preview, progress_);
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
}

void FrameLoop::write_frame(PendingFrame& pending) {
  const int f = pending.rendered.frame;
  try {
    pending.job->write(pending.rendered);
    pending.claim.release();
    std::lock_guard<std::mutex> lock(output_);
    progress_.clear();
    report_written(*pending.job, f, pending.rendered.path, pending.rendered.outcome);
  } catch (const Interrupted&) {
    return;  // no partial file is left (atomic_file.h); the claim goes with `pending`
  } catch (const std::bad_alloc&) {
    throw;
  } catch (const std::exception& e) {
    report_failure(f, e);
  }
  count_done(f);
}

void FrameLoop::wait_for_claimed_frames() {
  std::vector<int>& held = tallies_.held_elsewhere;
  if (!held.empty() && !options_.quiet) {
    progress_.clear();
    std::printf("waiting for %zu frame%s other processes are rendering: %s\n", held.size(), held.size() == 1 ? "" : "s",
                frame_list(held).c_str());
    std::fflush(stdout);
  }
  while (!held.empty() && interruption_signal() == 0) {
    sleep_unless_interrupted(kClaimPollSeconds);
    std::vector<int> waiting;
    waiting.swap(held);
    std::sort(waiting.begin(), waiting.end());
    for (size_t i = 0; i < waiting.size() && interruption_signal() == 0; ++i)
      if (std::shared_ptr<PendingFrame> pending = render_frame(*jobs_.front(), waiting[i], true)) write_frame(*pending);
  }
}

void FrameLoop::report_written(const FrameJob& job, int f, const std::string& path, const FrameOutcome& outcome) {
  if (++tallies_.rendered == 1) {
    tallies_.first_frame_memory = {host_rss_bytes(), first_device_ ? first_device_->allocated_bytes() : 0};
    tallies_.first_frame_ms = outcome.render_ms;
  }
  for (size_t j = 0; j < jobs_.size(); ++j) tallies_.frames_per_job[j] += jobs_[j].get() == &job ? 1 : 0;
  tallies_.reused += outcome.photons_reused ? 1 : 0;
  if (!options_.quiet) {
    std::printf("wrote %s (frame %d, %dx%d, %s, %.2f ms", path.c_str(), f, job.width(), job.height(),
                job.devices().c_str(), outcome.render_ms);
    if (outcome.result.passes > 1 || options_.budget.open_ended())
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
                 f, 100.0 * outcome.result.error, 100.0 * options_.budget.target_error);
}

void FrameLoop::report_failure(int f, const std::exception& e) {
  if (todo_.size() == 1 && options_.selected_frames == 1) throw;  // a single frame: main() reports it as before
  std::lock_guard<std::mutex> lock(output_);
  progress_.clear();
  std::fprintf(stderr, "pmrender: frame %d: %s\n", f, e.what());
  tallies_.failed.push_back(f);
}

void FrameLoop::count_done(int f) {
  std::lock_guard<std::mutex> lock(output_);
  progress_.show_count("frame " + std::to_string(f), ++done_, todo_.size(), seconds(), "frame");
}

}  // namespace pm::cli
