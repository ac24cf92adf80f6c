// The seam between the frame pipeline and the ways of computing indirect light. A frame is the
// camera pass (S5, the renderer's), then one or more passes of a method, each adding its
// estimate to the film's indirect and caustic sums, then the film resolve (S7, the renderer's),
// which divides by the pass count. Photon mapping (render/photon/) is one method; every method
// shares the scene, the camera pass, the film and the device, and owns its buffers (its group in
// PM_BUFFER_LIST) and its stages. The renderer and the benchmarks drive a method through this
// interface only (docs/architecture.md, "Adding a method").
#pragma once

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "render/buffer_table.h"
#include "render/device.h"
#include "render/error_forecast.h"
#include "render/scene.h"
#include "render/scene_scale.h"
#include "render/stage_timer.h"

namespace pm {

class IndirectMethod;
class MethodSettings;

// Host work a method can begin from the scene alone, before its renderer uploads the scene
// (radiosity's refined mesh and elements), on a thread of its own: the renderer begins it first,
// so that it runs beside the scene's BVH build and upload (447 ms for Conference on the H200's
// host, about as long as the mesh), and hands it to the method it creates
// (MethodSettings::begin_host_work). --method auto begins it once for the candidates it serves.
class HostWorkAhead {
 public:
  virtual ~HostWorkAhead() = default;
  // Whether this is the work `settings` would begin on the same scene.
  virtual bool serves(const MethodSettings& settings, const SceneMeasures& measures) const = 0;
};

// What a method works with, for its whole life.
struct MethodContext {
  Device& device;
  const Scene& scene;
  const SceneMeasures& measures;
  BufferTable& buffers;
  int width, height;        // the film
  uint32_t shading_points;  // camera-pass records: width * height * (mirror depth + 1)
  uint32_t planned_passes;  // passes per frame the renderer will ask for (RenderSettings::passes)
  std::shared_ptr<const HostWorkAhead> host_work;  // begun for it (begin_host_work); may be null
};

// A frame's work in the method's own unit (IndirectMethod::work).
struct MethodWork {
  std::string unit;         // "photon", "path", "element"
  double total = 0;         // over the passes asked for
  double largest_pass = 0;  // the most one of those passes did
};

// Named figures a method reports about the last frame: for logs, EXR headers (pmrender/NAME)
// and benchmarks.
struct MethodStats {
  struct Entry {
    std::string name;
    double value = 0;
  };
  std::vector<Entry> entries;
  void set(const std::string& name, double value);
  bool has(const std::string& name) const;
  double get(const std::string& name, double fallback = 0) const;
};

// What changed since the previous frame the method saw (geometry never changes).
struct FrameChange {
  bool first = true;   // no frame before on this renderer
  bool lights = true;  // a light moved or changed power
  bool camera = true;  // the camera moved (the camera pass ran again either way)
};

// The frame a method is asked to work on.
struct FrameContext {
  int frame = 0;
  // The first frame of the run of consecutive frames sharing this frame's lights: work that
  // depends on the lights only may be keyed by it and reused across the run (docs/animation.md).
  int light_run_start = 0;
  bool reuse_lighting = true;  // RenderSettings::reuse_lighting
  const std::vector<LightDesc>* lights = nullptr;
  LaunchParams params{};       // the renderer's fields: camera, film size, lights, seed, frame
  StageTimer* timer = nullptr;
  bool collect_stats = false;  // benchmarks: count per-stage work (costs atomics)
};

// A method's settings: validated and turned into the method.
class MethodSettings {
 public:
  virtual ~MethodSettings() = default;
  virtual const char* method_name() const = 0;
  // Throws SettingError naming the setting that is out of range.
  virtual void validate() const = 0;
  virtual std::unique_ptr<IndirectMethod> create(const MethodContext& context) const = 0;
  // Begins the host work its method's first frame needs that depends on the scene alone (see
  // HostWorkAhead); null where there is none, or where the settings would be refused for the
  // scene (create refuses them then).
  virtual std::shared_ptr<const HostWorkAhead> begin_host_work(const Scene& /*scene*/,
                                                               const SceneMeasures& /*measures*/) const {
    return nullptr;
  }
};

class IndirectMethod {
 public:
  virtual ~IndirectMethod() = default;

  // The settings as resolved for this scene (defaults filled in), one line for headers and logs.
  virtual std::string describe() const = 0;
  // The most passes a frame can use; 0: any number (a progressive method).
  virtual uint32_t max_passes() const = 0;
  // The diffuse and glossy bounces of indirect light it estimates (--bounces), and whether it
  // may be biased: the error estimate's bias control path-traces those light paths beside a
  // biased method's film (render/bias_control.h); an unbiased one needs no control.
  virtual uint32_t light_bounces() const = 0;
  virtual bool may_be_biased() const = 0;
  // Whether its passes are independent samples of one estimate (the path tracer's paths, final
  // gathering's rays over a fixed radiosity solution): their error falls as noise does until a
  // bias shows. Photon passes are not: they trace a new map each pass, and shrinking ones change
  // its bias as they go (--method auto forecasts them more slowly; render/method_race.h).
  virtual bool passes_are_samples() const { return true; }
  // How fast a pixel's noise falls with the passes, as passes^-rate (render/error_forecast.h):
  // kIndependentNoiseRate for independent samples, kScrambledNetRate where the passes' rays are
  // points of scrambled (0,2)-sequences (final gathering, kernels/common/low_discrepancy.h).
  virtual double noise_rate() const { return kIndependentNoiseRate; }

  // Takes over what `other`, a method on the same device and scene that has begun a frame, built
  // that does not depend on the frame and that this method would build the same (radiosity's
  // mesh and links), by copies on the device, rather than building it again in begin_frame.
  // Returns whether it did; the image is the same either way. --method auto's race shares work
  // between its candidates so (render/method_race.h).
  virtual bool adopt_setup(const IndirectMethod& /*other*/) { return false; }
  // Whether adopt_setup(other) takes over other's setup once other has begun a frame.
  virtual bool shares_setup_with(const IndirectMethod& /*other*/) const { return false; }

  // Where the method can measure its own bias directly, a kernel that does along the error
  // control's paths (control: the frame's parameters with the control's fields set, as
  // kernel_bias_control takes them; work_items its items), writing, per work item, the sums of
  // each path's own estimate less the method's along the path's first direction into
  // control_partials:
  // final gathering over radiosity (kernels/common/radiosity_bias_probe.h), whose bias is its
  // solution's one bounce away and does not fall with its passes. --method auto reads it as the
  // floor under that candidate's error (render/method_race.h).
  virtual bool has_bias_probe() const { return false; }
  virtual void launch_bias_probe(const FrameContext& /*frame*/, const LaunchParams& /*control*/,
                                 uint64_t /*work_items*/) {}
  // Once per frame, before its passes. change says what differs from the previous frame.
  virtual void begin_frame(const FrameContext& frame, const FrameChange& change) = 0;
  // Pass `pass` (0, 1, ...) of the frame: adds its estimate, weighted 1, into film_indirect_sum
  // and film_caustic_sum; the film resolve divides by the number of passes.
  virtual void run_pass(const FrameContext& frame, uint32_t pass) = 0;

  // About the last frame.
  virtual MethodStats stats() const = 0;
  // The method's stages in the order they run, with their work per frame for throughput.
  virtual std::vector<StageInfo> stages(const FrameContext& frame) const = 0;
  // The unit of the method's work and how much of it a frame's first `passes` passes do
  // ("photon": 262144 a pass, more in final gathering's later passes), with its largest pass
  // among them, for bytes per unit.
  virtual MethodWork work(uint32_t passes) const = 0;
};

}  // namespace pm
