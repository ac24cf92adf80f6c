// Orchestration of the vertex link radiosity stages over the Device interface and the buffer
// table's radiosity group (vertex_link_radiosity.h).
#include "render/radiosity/vertex_link_radiosity.h"

#include <algorithm>
#include <cmath>
#include <future>

#include "kernels/common/pixel_order.h"
#include "render/errors.h"
#include "render/radiosity/mesh_refinement.h"
#include "render/radiosity/radiosity_elements.h"
#include "render/radiosity/radiosity_texture_tint.h"

namespace pm {

// The first frame's host work: the refined mesh, its elements and, in a textured scene, the
// elements' texture colours (sampled from the packed images the device has).
struct RadiosityHostMesh {
  RefinedMesh mesh;
  RadiosityElements elements;
  std::vector<float4> tints;
};

namespace {

std::shared_ptr<const RadiosityHostMesh> build_host_mesh(const Scene& scene, RadiositySettings settings) {
  auto built = std::make_shared<RadiosityHostMesh>();
  built->mesh = refine_mesh(scene, settings.max_edge);
  built->elements = build_radiosity_elements(scene, built->mesh, settings.feature_angle, settings.sides == 2);
  if (scene.has_textures()) {
    DeviceTextures textures;
    pack_texture_images(scene, &textures);
    built->tints = radiosity_texture_tints(scene, built->mesh, built->elements, textures);
  }
  return built;
}

}  // namespace

// The host mesh on a thread of its own (the scene outlives it: renderers and the race keep a
// reference to their scene), for the settings it was begun with.
class RadiosityHostWork final : public HostWorkAhead {
 public:
  RadiosityHostWork(const Scene& scene, const RadiositySettings& resolved)
      : settings_(resolved), mesh_(std::async(std::launch::async, build_host_mesh, std::cref(scene), resolved).share()) {}
  bool serves(const MethodSettings& settings, const SceneMeasures& measures) const override {
    const auto* radiosity = dynamic_cast<const RadiositySettings*>(&settings);
    return radiosity && radiosity->resolved(measures).same_mesh_as(settings_);
  }
  std::shared_ptr<const RadiosityHostMesh> mesh() const { return mesh_.get(); }

 private:
  RadiositySettings settings_;
  std::shared_future<std::shared_ptr<const RadiosityHostMesh>> mesh_;
};

std::shared_ptr<const HostWorkAhead> begin_radiosity_host_mesh(const Scene& scene, const RadiositySettings& resolved) {
  if (resolved.solution_bounces() == 0 || estimate_refined_triangles(scene, resolved.max_edge) > double(kMaxRefinedTriangles))
    return nullptr;
  return std::make_shared<RadiosityHostWork>(scene, resolved);
}

VertexLinkRadiosity::VertexLinkRadiosity(const MethodContext& context, const RadiositySettings& settings)
    : device_(context.device),
      buffers_(context.buffers),
      scene_(context.scene),
      settings_(settings.resolved(context.measures)) {
  settings_.validate();
  const auto begun = std::dynamic_pointer_cast<const RadiosityHostWork>(context.host_work);
  if (begun && begun->serves(settings, context.measures)) host_work_ = begun;
  pixels_ = uint32_t(context.width) * uint32_t(context.height);
  planned_passes_ = std::max(context.planned_passes, 1u);
  // Refused before any work: a max_edge that would refine the scene into too many triangles.
  const double estimate = estimate_refined_triangles(scene_, settings_.max_edge);
  if (estimate > double(kMaxRefinedTriangles))
    throw SettingError("max-edge", std::to_string(settings_.max_edge) + " m would refine the scene into about " +
                                       std::to_string(uint64_t(estimate)) + " triangles (at most " +
                                       std::to_string(kMaxRefinedTriangles) + "); use a larger --max-edge");
}

LaunchParams VertexLinkRadiosity::launch_params(const FrameContext& frame) const { return with_solution(frame.params); }

LaunchParams VertexLinkRadiosity::with_solution(LaunchParams p) const {
  p.element_count = element_count_;
  p.link_directions = settings_.directions;
  p.light_sampling = uint32_t(settings_.light_samples);
  p.link_origins = uint32_t(settings_.link_origins);
  p.feature_cos = float(std::cos(double(settings_.feature_angle) * M_PI / 180.0));
  p.link_hidden_distance = settings_.hidden_origins * settings_.max_edge;
  return p;
}

std::vector<StageInfo> VertexLinkRadiosity::stages(const FrameContext& frame) const {
  const double elements = element_count_, lights = frame.lights ? double(frame.lights->size()) : 1.0;
  return {
      {"radiosity: refine", double(scene_.triangle_count()), "triangles/s", "scene triangles refined (first frame)"},
      {"radiosity: links", elements * settings_.directions, "rays/s", "link rays, nC per element (first frame)"},
      {"radiosity: light links", double(light_samples_) * lights, "rays/s", "shadow rays, all lights (light changes)"},
      {"radiosity: gather", double(links_) * settings_.solution_bounces(), "links/s", "links read, all bounces"},
      {"radiosity: smooth", elements * settings_.smooth_passes, "elements/s", "elements smoothed, all passes"},
      settings_.final_gather > 0
          ? StageInfo{"radiosity: final gather", double(pixels_) * settings_.final_gather * planned_passes_,
                      "rays/s", "gather rays per frame, every pass"}
          : StageInfo{"radiosity: interpolate", double(pixels_), "pixels/s", "pixels interpolated (every frame)"},
  };
}

// Refinement, elements and their upload ("radiosity: refine", host work between two device
// markers, so it is timed like a device stage; what was begun before the renderer's upload is
// waited for there).
void VertexLinkRadiosity::prepare(StageTimer* timer) {
  StageScope scope(timer, "radiosity: refine");
  const std::shared_ptr<const RadiosityHostMesh> built = host_work_ ? host_work_->mesh() : build_host_mesh(scene_, settings_);
  host_work_.reset();  // the mesh's host memory goes with the last holder
  const RefinedMesh& mesh = built->mesh;
  const RadiosityElements& elements = built->elements;
  element_count_ = uint32_t(elements.count());
  ranges_ = elements.ranges;
  count_light_samples();
  buffers_.upload(BufferSlot::rad_elements, elements.data);
  buffers_.upload(BufferSlot::rad_tree, mesh.tree);
  buffers_.upload(BufferSlot::rad_triangles, elements.triangles);
  buffers_.upload(BufferSlot::rad_adjacency, elements.adjacency);
  buffers_.upload(BufferSlot::rad_smooth_weights, elements.smooth_weights);
  buffers_.upload(BufferSlot::rad_element_ranges, ranges_);
  if (scene_.has_textures()) buffers_.upload(BufferSlot::rad_texture_tint, built->tints);
  BufferExtents extents;
  extents.elements = element_count_;
  buffers_.allocate(BufferGroup::radiosity, extents);
  buffers_.bind_all();
  prepared_ = true;

  mesh_stats_ = MethodStats{};
  mesh_stats_.set("elements", element_count_);
  mesh_stats_.set("vertices", double(elements.vertices_with_elements));
  mesh_stats_.set("scene_vertices", double(mesh.welded_vertices));
  mesh_stats_.set("refined_triangles", double(mesh.triangle_count()));
  mesh_stats_.set("tree_depth", mesh.depth);
}

// Light-link shadow rays per light and run: one per element, or four per one-ring triangle.
void VertexLinkRadiosity::count_light_samples() {
  light_samples_ = 0;
  for (uint32_t e = 0; e < element_count_; ++e) {
    const uint64_t ring = ranges_[e + 1].x - ranges_[e].x;
    light_samples_ += settings_.light_samples == PM_RADIOSITY_LIGHT_VERTEX ? 1 : 4 * ring;
  }
}

// Another renderer's radiosity on the same device and scene, whose mesh and links are the ones
// this one would build (same_links_as).
bool VertexLinkRadiosity::shares_setup_with(const IndirectMethod& other_method) const {
  const auto* other = dynamic_cast<const VertexLinkRadiosity*>(&other_method);
  return other && other != this && &other->device_ == &device_ && &other->scene_ == &scene_ &&
         settings_.same_links_as(other->settings_);
}

// The mesh and links of such a renderer, once it has built them, copied on the device: what
// prepare() and build_links() would have made here, without refining or tracing again.
bool VertexLinkRadiosity::adopt_setup(const IndirectMethod& other_method) {
  const auto* other = dynamic_cast<const VertexLinkRadiosity*>(&other_method);
  if (prepared_ || !shares_setup_with(other_method) || !other->prepared_) return false;
  for (BufferSlot slot : {BufferSlot::rad_elements, BufferSlot::rad_tree, BufferSlot::rad_triangles,
                          BufferSlot::rad_adjacency, BufferSlot::rad_smooth_weights, BufferSlot::rad_element_ranges,
                          BufferSlot::rad_texture_tint, BufferSlot::rad_links})
    buffers_.copy_from(slot, other->buffers_[slot]);
  element_count_ = other->element_count_;
  ranges_ = other->ranges_;
  count_light_samples();
  link_capacity_ = other->link_capacity_;
  links_ = other->links_;
  link_words_ = other->link_words_;
  raw_links_ = other->raw_links_;
  link_batches_ = other->link_batches_;
  batch_elements_ = other->batch_elements_;
  mesh_stats_ = other->mesh_stats_;
  BufferExtents extents;
  extents.elements = element_count_;
  buffers_.allocate(BufferGroup::radiosity, extents);
  buffers_.bind_all();
  prepared_ = adopted_ = true;
  return true;
}

// Grows rad_links to hold `words`, keeping the first `used` (a device copy).
void VertexLinkRadiosity::resize_links(uint64_t words, uint64_t used) {
  DeviceBuffer links = device_.allocate(std::max<uint64_t>(words, 1) * 4, "rad_links");
  if (used > 0) device_.copy(buffers_[BufferSlot::rad_links], links, used * 4);
  buffers_[BufferSlot::rad_links] = std::move(links);
  link_capacity_ = words;
  buffers_.bind_all();
}

// Link generation in batches ("radiosity: links"): trace and merge on the device, the batch's
// word counts to the host for the offsets (a prefix sum), encode and store on the device.
void VertexLinkRadiosity::build_links(LaunchParams p, StageTimer* timer) {
  StageScope scope(timer, "radiosity: links");
  const uint32_t elements = element_count_, nc = settings_.directions;
  batch_elements_ = settings_.batch_elements(elements);
  BufferExtents extents;
  extents.elements = elements;
  extents.link_batch = batch_elements_;
  extents.link_scratch = uint64_t(batch_elements_) * nc * 3;
  buffers_.allocate(BufferGroup::radiosity, extents);
  resize_links(uint64_t(elements) * nc, 0);  // a first guess: about one link per ray

  std::vector<uint32_t> counts(4 * size_t(batch_elements_));
  uint64_t total = 0;
  links_ = raw_links_ = 0;
  link_batches_ = 0;
  for (uint32_t first = 0; first < elements; first += batch_elements_) {
    const uint32_t count = std::min(batch_elements_, elements - first);
    p.batch_first = first;
    p.batch_count = count;
    device_.launch(KernelId::radiosity_link_trace, count * nc, p);
    device_.launch(KernelId::radiosity_link_merge, count, p);
    device_.download(buffers_[BufferSlot::rad_batch_counts], counts.data(), 4 * size_t(count) * sizeof(uint32_t));
    const uint64_t used = total;
    for (uint32_t i = 0; i < count; ++i) {
      ranges_[first + i].w = counts[4 * i + 2];  // hidden link origins (radiosity_links.h)
      counts[4 * i + 2] = uint32_t(total);
      ranges_[first + i].z = uint32_t(total);
      total += counts[4 * i];
      raw_links_ += counts[4 * i + 1];
      links_ += counts[4 * i + 3];
    }
    if (total > 0xffffffffull)
      throw SettingError("directions", "the links exceed 2^32 words; use fewer directions or a larger --max-edge");
    if (total > link_capacity_) resize_links(std::max(total, link_capacity_ + link_capacity_ / 4), used);
    device_.upload(buffers_[BufferSlot::rad_batch_counts], counts.data(), 4 * size_t(count) * sizeof(uint32_t));
    device_.launch(KernelId::radiosity_link_store, count, p);
    ++link_batches_;
  }
  ranges_[elements].z = uint32_t(total);
  link_words_ = total;
  if (link_capacity_ > total + total / 16) resize_links(total, total);  // no growth slack kept
  buffers_.upload(BufferSlot::rad_element_ranges, ranges_);
  extents.link_batch = extents.link_scratch = 0;  // the scratch is freed
  buffers_.allocate(BufferGroup::radiosity, extents);
  buffers_.bind_all();
  ++link_builds_;
}

// Light links, gathering and smoothing: the vertex irradiance for the current lights.
void VertexLinkRadiosity::solve(LaunchParams p, StageTimer* timer) {
  const uint32_t elements = element_count_;
  {
    StageScope scope(timer, "radiosity: light links");
    device_.launch(KernelId::radiosity_light_links, elements, p);
  }
  {
    StageScope scope(timer, "radiosity: gather");
    for (int bounce = 0; bounce < settings_.solution_bounces(); ++bounce) {
      p.radiosity_source = uint32_t(bounce & 1);
      device_.launch(KernelId::radiosity_gather, elements, p);
    }
  }
  uint32_t source = 0;
  {
    StageScope scope(timer, "radiosity: smooth");
    for (int pass = 0; pass < settings_.smooth_passes; ++pass) {
      p.radiosity_source = source;
      device_.launch(KernelId::radiosity_smooth, elements, p);
      source ^= 1u;
    }
  }
  final_source_ = source;
  solved_ = true;
  ++light_link_runs_;
}

void VertexLinkRadiosity::begin_frame(const FrameContext& frame, const FrameChange& change) {
  bool built = false, lit = false;
  // The gather rays' key: as the photon method's photons, the first frame of a run sharing its
  // lights (camera-only frames then show the same noise rather than flicker), unless --no-reuse.
  ray_frame_ = frame.reuse_lighting ? frame.light_run_start : frame.frame;
  // A solution of no bounces (final gathering with --bounces 1) holds nothing: the gather rays
  // bring the direct light at their hits alone.
  if (settings_.solution_bounces() == 0) {
    update_stats(false, false);
    return;
  }
  if (!prepared_) {
    prepare(frame.timer);
    if (element_count_ > 0) build_links(launch_params(frame), frame.timer);
    built = true;
  }
  // --no-reuse: the lighting of every frame is computed afresh (links stay: geometry is static).
  const bool relight = built || change.first || change.lights || !solved_ || !frame.reuse_lighting;
  if (element_count_ > 0 && relight) {
    solve(launch_params(frame), frame.timer);
    lit = true;
  }
  update_stats(built, lit);
}

void VertexLinkRadiosity::run_pass(const FrameContext& frame, uint32_t /*pass*/) {
  LaunchParams p = launch_params(frame);
  p.radiosity_source = final_source_;
  if (settings_.final_gather > 0) {
    // Rays of pass k are rays k N .. k N + N - 1 of the frame (final_gather.h; pass_index is the
    // renderer's).
    p.final_gather_rays = settings_.final_gather;
    p.photon_frame = uint32_t(ray_frame_);
    StageScope scope(frame.timer, "radiosity: final gather");
    device_.launch(KernelId::radiosity_final_gather, pixel_work_items(p.width, p.height), p);
    return;
  }
  if (element_count_ == 0) return;
  StageScope scope(frame.timer, "radiosity: interpolate");
  device_.launch(KernelId::radiosity_interpolate, pixel_work_items(p.width, p.height), p);
}

void VertexLinkRadiosity::launch_bias_probe(const FrameContext& /*frame*/, const LaunchParams& control,
                                            uint64_t work_items) {
  LaunchParams p = with_solution(control);
  p.radiosity_source = final_source_;
  device_.launch(KernelId::radiosity_bias_probe, work_items, p);
}

void VertexLinkRadiosity::update_stats(bool built, bool lit) {
  stats_ = mesh_stats_;
  // The links' words and their per-element offsets (the ranges' link column).
  const uint64_t link_bytes = link_words_ * 4 + uint64_t(element_count_ + 1) * 4;
  stats_.set("link_rays", double(element_count_) * settings_.directions);
  stats_.set("links", double(links_));
  stats_.set("links_raw", double(raw_links_));
  stats_.set("link_bytes", double(link_bytes));
  stats_.set("link_bytes_raw", double(raw_links_) * 8);
  stats_.set("bytes_per_link", links_ ? double(link_bytes) / double(links_) : 0.0);
  stats_.set("link_batches", link_batches_);
  stats_.set("batch_elements", batch_elements_);
  stats_.set("light_rays_per_light", double(light_samples_));
  stats_.set("link_builds", double(link_builds_));
  stats_.set("light_link_runs", double(light_link_runs_));
  stats_.set("links_built", built ? 1 : 0);
  stats_.set("links_adopted", adopted_ ? 1 : 0);
  stats_.set("light_links_run", lit ? 1 : 0);
  stats_.set("radiosity_bytes", double(buffers_.bytes(BufferGroup::radiosity)));
}

}  // namespace pm
