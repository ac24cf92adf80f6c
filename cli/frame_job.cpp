// A frame's passes, checkpoints, progress and file.
#include "cli/frame_job.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "render/checkpoint.h"
#include "render/exr_io.h"
#include "render/preview_png.h"
#include "render/scene_frame.h"

namespace pm::cli {

namespace {

// A statistic for an EXR header: integers without a fraction, others with full precision.
std::string number_text(double v) {
  char text[32];
  if (v == double(int64_t(v)) && std::fabs(v) < 1e15) std::snprintf(text, sizeof(text), "%lld", (long long)v);
  else std::snprintf(text, sizeof(text), "%.9g", v);
  return text;
}

std::string percent_text(double error) {
  if (error < 0) return "-";
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f%%", 100.0 * error);
  return text;
}

}  // namespace

FrameJob::FrameJob(RendererPool& pool, const Scene& scene, const FrameJobOptions& options)
    : pool_(pool), renderer_(pool.first()), scene_(scene), options_(options) {
  fingerprint_ = scene.name + " (" + scene.source + ") " + renderer_.describe();
  backend_ = renderer_.device().info().backend;
  for (size_t i = 0; i < pool.size(); ++i)
    device_names_ += (i ? ", " : "") + pool.renderer(i).device().info().name;
}

void FrameJob::continue_from(int frame, FilmSums sums, double seconds) {
  continuation_ = Continuation{frame, std::move(sums), seconds};
}

void FrameJob::add_attributes(const std::vector<std::pair<std::string, std::string>>& extra) {
  extra_attributes_.insert(extra_attributes_.end(), extra.begin(), extra.end());
}

std::vector<std::pair<std::string, std::string>> FrameJob::attributes(int frame, const PassReport& report,
                                                                      const std::string& stopped_by) const {
  std::vector<std::pair<std::string, std::string>> a = {
      {"pmrender/version", PMRENDER_VERSION},
      {"pmrender/scene", scene_.name + " (" + scene_.source + ")"},
      {"pmrender/frame", std::to_string(frame)},
      {"pmrender/time", std::to_string(frame_time(scene_, frame))},
      {"pmrender/backend", backend_},
      {"pmrender/device", device_names_},
      {"pmrender/settings", renderer_.describe()},
      {"pmrender/passes", std::to_string(report.passes)},
      {"pmrender/render_seconds", number_text(report.seconds)}};
  if (!stopped_by.empty()) a.push_back({"pmrender/stopped_by", stopped_by});
  if (report.error >= 0) a.push_back({"pmrender/error_estimate", number_text(report.error)});
  if (const BiasEstimate& bias = renderer_.last_bias(); bias.known) {
    // What the control saw (render/bias_control.h): the estimate's upper end, the regional
    // |bias|, the signed bias of the control pixels' sum with its standard error, and the
    // control's paths per pixel.
    a.push_back({"pmrender/error_estimate_upper", number_text(bias.mean_abs_error_upper)});
    a.push_back({"pmrender/error_rms", number_text(bias.rms_error)});
    a.push_back({"pmrender/error_bias", number_text(bias.regional_bias)});
    a.push_back({"pmrender/error_bias_signed", number_text(bias.signed_bias)});
    a.push_back({"pmrender/error_bias_stderr", number_text(bias.bias_error)});
    a.push_back({"pmrender/error_control_paths", std::to_string(bias.paths)});
    // Of the estimate, the part the film's own noise does not explain (its even/odd passes).
    if (bias.bias_floor >= 0) a.push_back({"pmrender/error_bias_floor", number_text(bias.bias_floor)});
  }
  a.insert(a.end(), extra_attributes_.begin(), extra_attributes_.end());
  for (auto& layer_attribute : film_layer_attributes(renderer_.layers(), scene_, options_.full_float))
    a.push_back(std::move(layer_attribute));
  if (const IndirectMethod* method = renderer_.method()) {
    const MethodWork work = method->work(report.passes);
    a.push_back({"pmrender/" + work.unit + "s_total", number_text(work.total)});
    for (const MethodStats::Entry& e : method->stats().entries) a.push_back({"pmrender/" + e.name, number_text(e.value)});
  }
  return a;
}

RenderedFrame FrameJob::render(int frame, const std::string& path, const std::string& preview,
                              ProgressLine& progress) {
  RenderedFrame rendered;
  rendered.frame = frame;
  rendered.path = path;
  rendered.preview = preview;
  FrameOutcome& outcome = rendered.outcome;
  const std::string state_path = checkpoint_state_path(path);
  std::optional<FrameCheckpoint> checkpoint;
  if (options_.resume && std::filesystem::exists(state_path)) {
    std::string why;
    checkpoint = read_checkpoint(state_path, frame, renderer_.width(), renderer_.height(), fingerprint_, &why);
    if (!checkpoint && !options_.quiet)
      std::fprintf(stderr, "pmrender: warning: frame %d: not continuing from %s (%s); starting over\n", frame,
                   state_path.c_str(), why.c_str());
  }
  outcome.resumed = checkpoint.has_value();

  const uint32_t cap = options_.budget.max_passes;
  const IndirectMethod* method = renderer_.method();
  // Plain variables, not a structured binding: C++17 lambdas cannot capture bindings.
  const std::string unit = method ? method->work(1).unit : "";
  auto last_draw = std::chrono::steady_clock::time_point{};
  ProgressiveCallbacks callbacks;
  // --verbose under a target error: the control's reading each time the passes double (and the
  // bias it sees beside the film's own noise), so that a frame that levels off shows why.
  const bool log_readings = options_.verbose && options_.budget.target_error > 0 && pass_progress_;
  auto log_reading = [&](const PassReport& r) {
    if (!log_readings || r.error < 0 || r.passes < kMinPassesForError || (r.passes & (r.passes - 1)) != 0) return;
    const BiasEstimate& b = renderer_.last_bias();
    // Without a control reading the estimate is the even/odd noise alone, and says so.
    std::string detail = "noise only";
    if (b.known) {
      detail = "+-" + percent_text(b.mean_abs_error_stderr);
      if (b.bias_floor >= 0) detail += ", bias at least " + percent_text(b.bias_floor);
    }
    std::lock_guard<std::mutex> lock(*pass_progress_);
    progress.clear();
    std::printf("frame %d: %u passes in %s, error %s (%s)\n", frame, r.passes, seconds_text(r.seconds).c_str(),
                percent_text(r.error).c_str(), detail.c_str());
    std::fflush(stdout);
  };
  if (pass_progress_) callbacks.after_pass = [&](const PassReport& r) {
    log_reading(r);
    const auto now = std::chrono::steady_clock::now();
    if (now - last_draw < std::chrono::milliseconds(100)) return;
    last_draw = now;
    // What is left: the time budget's rest, the passes the error needs at 1/sqrt(passes), or the cap's.
    const double per_pass_s = r.seconds / double(r.passes);
    double eta = per_pass_s * double(cap - std::min(cap, r.passes));
    if (options_.budget.target_error > 0 && r.error > 0)
      eta = std::min(eta, per_pass_s * std::max(0.0, r.passes * std::pow(r.error / options_.budget.target_error, 2) - r.passes));
    if (options_.budget.seconds > 0) eta = std::min(eta, std::max(0.0, options_.budget.seconds - r.seconds));
    char text[256];
    std::snprintf(text, sizeof(text), "frame %d  pass %u%s  %.3g %ss  error %s  ETA %s", frame, r.passes,
                  options_.budget.open_ended() ? "" : ("/" + std::to_string(cap)).c_str(), method ? method->work(r.passes).total : 0.0,
                  unit.c_str(), percent_text(r.error).c_str(), seconds_text(eta).c_str());
    std::lock_guard<std::mutex> lock(*pass_progress_);
    progress.show(text);
  };
  callbacks.checkpoint = [&](const PassReport& r) {
    FrameCheckpoint c;
    c.frame = frame;
    c.width = renderer_.width();
    c.height = renderer_.height();
    c.seconds = r.seconds;
    c.fingerprint = fingerprint_;
    c.sums = renderer_.film_sums();
    write_checkpoint(state_path, c);
    FrameImage image = renderer_.read_image();
    image.attributes = attributes(frame, r, "");
    image.attributes.push_back({kCheckpointAttribute, std::to_string(r.passes)});
    write_exr(path, image, options_.full_float);
  };

  const FilmSums* resume = checkpoint ? &checkpoint->sums : nullptr;
  double resumed_seconds = checkpoint ? checkpoint->seconds : 0.0;
  std::optional<Continuation> continuation;
  if (continuation_ && continuation_->frame == frame) continuation.swap(continuation_);
  if (continuation && !checkpoint) {
    resume = &continuation->sums;
    resumed_seconds = continuation->seconds;
  }
  const auto start = std::chrono::steady_clock::now();
  outcome.result = pool_.render_progressive(frame, options_.budget, resume, resumed_seconds, callbacks);
  FrameStats stats;
  FrameImage& image = rendered.image;
  image = renderer_.read_image(&stats);
  outcome.render_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  if (continuation && resume == &continuation->sums) outcome.render_ms += 1000.0 * continuation->seconds;  // the race's time too
  outcome.repaired_pixels = stats.repaired_pixels;
  outcome.photons_reused = method && method->stats().get("photons_reused") != 0;
  image.attributes = attributes(frame, outcome.result, outcome.result.stopped_by);
  image.attributes.push_back({"pmrender/render_ms", number_text(outcome.render_ms)});
  return rendered;
}

void FrameJob::write(const RenderedFrame& rendered) const {
  if (image_check_) image_check_(rendered.frame, rendered.image, rendered.outcome.repaired_pixels);
  write_exr(rendered.path, rendered.image, options_.full_float);
  std::error_code ignored;
  std::filesystem::remove(checkpoint_state_path(rendered.path), ignored);  // the frame is finished: its checkpoint is spent
  if (!rendered.preview.empty()) write_preview_png(rendered.preview, rendered.image, options_.preview_exposure_ev);
}

}  // namespace pm::cli
