// One frame of `pmrender render`, from the first pass to its file: the budgeted pass loop
// (render/progressive.h), checkpoints and their resume, the progress line inside the frame, and
// the EXR (and preview) with the header attributes that say how it was made.
#pragma once

#include <functional>
#include <mutex>
#include <optional>
#include <string>

#include "cli/progress_line.h"
#include "render/progressive.h"
#include "render/renderer.h"
#include "render/renderer_pool.h"

namespace pm::cli {

struct FrameJobOptions {
  PassBudget budget;
  bool full_float = false;
  bool resume = false;   // continue from a checkpoint where one fits
  bool quiet = false;
  bool verbose = false;  // under a target error: the error control's readings as the passes double
  std::optional<double> preview_exposure_ev;  // --exposure; without it each preview's automatic one
};

struct FrameOutcome {
  ProgressiveResult result;
  int repaired_pixels = 0;
  bool photons_reused = false;
  double render_ms = 0;
  bool resumed = false;  // continued from a checkpoint
};

// A frame rendered and read back, waiting for its file: FrameJob::write may run on another thread
// while the devices render the next frame.
struct RenderedFrame {
  int frame = 0;
  std::string path, preview;  // preview: empty for none
  FrameImage image;           // with the header attributes
  FrameOutcome outcome;
};

class FrameJob {
 public:
  // The pool's devices share each frame's passes (one device: the plain pass loop, checkpoints).
  FrameJob(RendererPool& pool, const Scene& scene, const FrameJobOptions& options);

  // Renders frame into path (and preview, when not empty) and returns what happened.
  FrameOutcome run(int frame, const std::string& path, const std::string& preview, ProgressLine& progress) {
    RenderedFrame rendered = render(frame, path, preview, progress);
    write(rendered);
    return rendered.outcome;
  }
  // run() in two steps: the passes (checkpoints included) and the image read back; then its file,
  // its preview and the end of its checkpoint. write() touches no device and no member that
  // render() changes, so it may overlap the next render().
  RenderedFrame render(int frame, const std::string& path, const std::string& preview, ProgressLine& progress);
  void write(const RenderedFrame& rendered) const;
  // Draw the pass progress inside a frame (only where one frame renders at a time), holding output
  // (the lock of everything printed, which a frame being written meanwhile takes too).
  void set_pass_progress(std::mutex* output) { pass_progress_ = output; }
  // Called by write() with each frame's image before its file is written (warnings about what the
  // file cannot hold), on the thread that writes it.
  using ImageCheck = std::function<void(int frame, const FrameImage& image, int repaired_pixels)>;
  void set_image_check(ImageCheck check) { image_check_ = std::move(check); }

  // The first render of `frame` goes on from these passes and counts their time (--method auto:
  // the race's winner, whose renderer the pool holds, has rendered them already).
  void continue_from(int frame, FilmSums sums, double seconds);
  // Header attributes written into every frame's EXR (--method auto's choice).
  void add_attributes(const std::vector<std::pair<std::string, std::string>>& extra);

  int width() const { return renderer_.width(); }
  int height() const { return renderer_.height(); }
  // "opencl: <device name>[, <name>...]".
  std::string devices() const { return backend_ + ": " + device_names_; }

 private:
  std::vector<std::pair<std::string, std::string>> attributes(int frame, const PassReport& report,
                                                               const std::string& stopped_by) const;

  RendererPool& pool_;
  Renderer& renderer_;  // the pool's first: its film holds the frame
  const Scene& scene_;
  std::string backend_, device_names_;
  FrameJobOptions options_;
  std::string fingerprint_;
  std::mutex* pass_progress_ = nullptr;  // not null: draw, holding it
  struct Continuation {
    int frame = 0;
    FilmSums sums;
    double seconds = 0;
  };
  std::optional<Continuation> continuation_;
  std::vector<std::pair<std::string, std::string>> extra_attributes_;
  ImageCheck image_check_;
};

}  // namespace pm::cli
