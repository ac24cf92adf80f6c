// Orchestration of the photon stages for one frame, batch by batch, over the Device interface.
#include "render/photon_pass.h"

#include <algorithm>
#include <cstring>
#include <cmath>
#include <numeric>
#include <sstream>

#include "kernels/common/photon_map.h"
#include "kernels/common/photon_map_stage.h"
#include "render/errors.h"
#include "render/footprint_scale.h"
#include "render/scene_scale.h"
#include "render/vvh_builder.h"

namespace pm {

namespace {

// Largest-remainder share of `total` photons by the lights' summed RGB power.
std::vector<uint32_t> share_by_power(const std::vector<LightDesc>& lights, uint32_t total) {
  std::vector<double> power;
  for (const LightDesc& l : lights) power.push_back(double(l.power.x) + l.power.y + l.power.z);
  double sum = std::accumulate(power.begin(), power.end(), 0.0);
  std::vector<uint32_t> share(power.size(), 0);
  if (sum <= 0) return share;
  std::vector<std::pair<double, size_t>> remainders;
  uint32_t given = 0;
  for (size_t i = 0; i < power.size(); ++i) {
    double exact = total * power[i] / sum;
    share[i] = uint32_t(std::floor(exact));
    given += share[i];
    remainders.push_back({exact - share[i], i});
  }
  std::sort(remainders.rbegin(), remainders.rend());
  for (size_t k = 0; given < total && k < remainders.size(); ++k, ++given) share[remainders[k].second]++;
  return share;
}

// The slots PhotonPass owns, in the order of buffers_.
const BufferSlot kOwnedSlots[] = {
    BufferSlot::hit_position,     BufferSlot::hit_normal,      BufferSlot::hit_incident,    BufferSlot::hit_flux,
    BufferSlot::hit_dp_u,         BufferSlot::hit_dp_v,        BufferSlot::footprint_lo,    BufferSlot::footprint_hi,
    BufferSlot::footprint_center, BufferSlot::footprint_row_u, BufferSlot::footprint_row_v, BufferSlot::footprint_row_n,
    BufferSlot::footprint_power,  BufferSlot::map_nodes,       BufferSlot::map_lo,          BufferSlot::map_hi,
    BufferSlot::map_center,       BufferSlot::map_row_u,       BufferSlot::map_row_v,       BufferSlot::map_row_n,
    BufferSlot::map_power,        BufferSlot::map_incident,    BufferSlot::footprint_cut,
    BufferSlot::map_cut,          BufferSlot::footprint_partials,
    BufferSlot::map_node_parent,  BufferSlot::map_leaf_parent, BufferSlot::map_visits};
constexpr size_t kFloat4Slots = 24;  // the first 24 hold one float4 per hit slot (or tile pair)

}  // namespace

std::string PhotonSettings::describe() const {
  static const char* estimators[] = {"pd", "radius", "knn"};
  std::ostringstream s;
  s << "photons=" << photons << " batch=" << batch << " bounces=" << bounces << " estimator=" << estimators[estimator]
    << " kernel=" << (kernel_shape == PM_KERNEL_EPANECHNIKOV ? "epanechnikov" : "constant") << " smoothing=";
  if (smoothing > 0) s << smoothing;
  else s << "auto";
  s << " rmax=" << rmax << " radius=" << radius << " photon_bvh=" << (vvh_map ? "vvh" : "lbvh") << " leaf=" << (leaf_threshold > 0 ? std::to_string(leaf_threshold) : "auto");
  if (sequence == PM_PHOTON_SEQUENCE_HALTON) s << " sequence=halton";
  return s.str();
}

PhotonPass::PhotonPass(Device& device, const Scene& scene, const PhotonSettings& settings)
    : device_(device), settings_(settings) {
  if (settings_.bounces < 0 || settings_.bounces > 16) throw InputError("--bounces: expected 0 to 16");
  if (settings_.batch == 0) throw InputError("--batch: must be at least 1");
  if (!(settings_.smoothing >= 0) || !std::isfinite(settings_.smoothing))
    throw InputError("--smoothing: must be positive (or auto)");
  if (settings_.rmax < 0 || !std::isfinite(settings_.rmax)) throw InputError("--rmax: must be positive");
  if (settings_.radius < 0 || !std::isfinite(settings_.radius)) throw InputError("--radius: must be positive");
  if (settings_.sequence != PM_PHOTON_SEQUENCE_RANDOM && settings_.sequence != PM_PHOTON_SEQUENCE_HALTON)
    throw InputError("--photon-sequence: expected random or halton");
  scene_area_ = scene_surface_area(scene);
  const double diagonal = scene_diagonal(scene);
  if (settings_.rmax == 0) settings_.rmax = float(0.1 * diagonal);
  if (settings_.radius == 0) settings_.radius = float(0.05 * diagonal);

  if (settings_.photons > 0xffffffffull)  // photon i draws from random stream i, a 32-bit number
    throw InputError("--photons: at most 4294967295 (2^32 - 1) photons per frame, got " + std::to_string(settings_.photons));
  batch_count_ = uint32_t((settings_.photons + settings_.batch - 1) / settings_.batch);
  const uint64_t per_batch = batch_count_ ? (settings_.photons + batch_count_ - 1) / batch_count_ : 0;
  slots_per_photon_ = uint32_t(settings_.bounces + 2);
  if (per_batch * slots_per_photon_ > (1u << 29))
    throw InputError("--batch: " + std::to_string(per_batch) + " photons per batch need more than 2^29 hit records; "
                     "use a smaller --batch (more passes)");
  batch_size_ = uint32_t(per_batch);
  per_light_ = share_by_power(scene.lights, batch_size_);
  if (batch_size_ > 0) allocate();
}

void PhotonPass::set_lights(const std::vector<LightDesc>& lights) {
  per_light_ = share_by_power(lights, batch_size_);
  map_intact_ = false;
}

void PhotonPass::allocate() {
  const size_t slots = size_t(batch_size_) * slots_per_photon_;
  const size_t tiles = (slots + PM_PHOTON_MAP_BOUNDS_TILE - 1) / PM_PHOTON_MAP_BOUNDS_TILE;
  for (size_t i = 0; i < std::size(kOwnedSlots); ++i) {
    size_t bytes;
    if (kOwnedSlots[i] == BufferSlot::map_nodes) bytes = 4 * slots * sizeof(float4);
    else if (kOwnedSlots[i] == BufferSlot::footprint_partials) bytes = 2 * tiles * sizeof(float4);
    else if (i < kFloat4Slots) bytes = slots * sizeof(float4);
    else bytes = slots * sizeof(uint32_t);
    buffers_.push_back(device_.allocate(bytes, buffer_slot_name(kOwnedSlots[i])));
    device_.bind(kOwnedSlots[i], buffers_.back());
  }
  sort_.keys = device_.allocate(slots * sizeof(uint32_t), "photon sort keys");
  sort_.values = device_.allocate(slots * sizeof(uint32_t), "photon sort values");
  sort_.keys_alt = device_.allocate(slots * sizeof(uint32_t), "photon sort keys (alternate)");
  sort_.values_alt = device_.allocate(slots * sizeof(uint32_t), "photon sort values (alternate)");
  stats_ = device_.allocate(2 * sizeof(uint32_t), "gather statistics");
  device_.bind(BufferSlot::gather_stats, stats_);
}

DeviceBuffer& PhotonPass::owned(BufferSlot slot) {
  for (size_t i = 0; i < buffers_.size(); ++i)
    if (kOwnedSlots[i] == slot) return buffers_[i];
  throw DeviceError(std::string("photon pass: no buffer for slot ") + buffer_slot_name(slot));
}

const DeviceBuffer* PhotonPass::buffer(BufferSlot slot) const {
  if (slot == BufferSlot::sort_keys) return &sort_.keys;
  if (slot == BufferSlot::sort_values) return &sort_.values;
  if (slot == BufferSlot::gather_stats) return &stats_;
  for (size_t i = 0; i < buffers_.size(); ++i)
    if (kOwnedSlots[i] == slot) return &buffers_[i];
  return nullptr;
}

LaunchParams PhotonPass::pass_params(const LaunchParams& frame) const {
  LaunchParams params = frame;
  params.photon_count = batch_size_;
  params.hit_slots_per_photon = slots_per_photon_;
  params.max_bounces = uint32_t(settings_.bounces);
  params.smoothing = settings_.smoothing;
  params.rmax = settings_.rmax;
  params.gather_radius = settings_.radius;
  params.knn_k = uint32_t(settings_.knn_k);
  params.estimator = uint32_t(settings_.estimator);
  params.kernel_shape = uint32_t(settings_.kernel_shape);
  params.batch_count = batch_count_;
  params.photon_sequence = uint32_t(settings_.sequence);
  return params;
}

void PhotonPass::bind() {
  for (size_t i = 0; i < buffers_.size(); ++i) device_.bind(kOwnedSlots[i], buffers_[i]);
  device_.bind(BufferSlot::gather_stats, stats_);
  device_.bind(BufferSlot::sort_keys, sort_.keys);
  device_.bind(BufferSlot::sort_values, sort_.values);
}

void PhotonPass::run(const LaunchParams& frame, PhotonStats* stats, StageTimer* timer) {
  map_intact_ = false;
  if (batch_size_ == 0) return;
  bind();
  LaunchParams params = pass_params(frame);
  if (params.collect_stats) device_.fill_zero(stats_, stats_.bytes());
  PhotonStats local;
  for (uint32_t b = 0; b < batch_count_; ++b) {
    params.photon_offset = b * batch_size_;
    run_batch(params, &local, timer);
  }
  local.batches = int(batch_count_);
  map_stats_ = local;
  map_intact_ = batch_count_ == 1;
  finish_stats(params, stats);
}

void PhotonPass::gather_again(const LaunchParams& frame, PhotonStats* stats, StageTimer* timer) {
  if (!map_intact_) throw DeviceError("photon pass: gather_again without an intact photon map");
  bind();
  LaunchParams params = pass_params(frame);
  params.photon_offset = 0;
  params.hit_bounds_lo = map_params_.hit_bounds_lo;
  params.hit_bounds_hi = map_params_.hit_bounds_hi;
  params.hit_count = map_params_.hit_count;
  params.leaf_threshold = map_params_.leaf_threshold;
  if (params.collect_stats) device_.fill_zero(stats_, stats_.bytes());
  map_intact_ = false;  // until this gather has gone through
  if (params.hit_count > 0) gather(params, timer);
  map_intact_ = true;
  finish_stats(params, stats);
}

void PhotonPass::finish_stats(const LaunchParams& params, PhotonStats* stats) {
  if (!stats) return;
  *stats = map_stats_;
  if (params.collect_stats) {
    uint32_t counts[2];
    device_.download(stats_, counts, sizeof(counts));
    stats->gathered = counts[0];
    stats->shading_points = counts[1];
  }
}

void PhotonPass::gather(const LaunchParams& params, StageTimer* timer) {
  StageScope scope(timer, Stage::gather);
  device_.launch(KernelId::gather, params.width * params.height, params);
}

// The VVH alternative to the device LBVH: the valid hits' footprint boxes go to the host, the
// tree comes back in the same node layout with its hit order as the "sorted" index, so the
// reorder kernel and the gather run unchanged.
void PhotonPass::build_vvh_map(const LaunchParams& params) {
  const size_t slots = size_t(batch_size_) * slots_per_photon_;
  std::vector<float4> lo(slots), hi(slots), center(slots);
  device_.download(owned(BufferSlot::footprint_lo), lo.data(), slots * sizeof(float4));
  device_.download(owned(BufferSlot::footprint_hi), hi.data(), slots * sizeof(float4));
  device_.download(owned(BufferSlot::footprint_center), center.data(), slots * sizeof(float4));
  std::vector<uint32_t> valid;
  std::vector<float4> valid_lo, valid_hi;
  for (uint32_t i = 0; i < slots; ++i) {
    uint32_t flags;
    std::memcpy(&flags, &center[i].w, 4);
    if (!(flags & PM_HIT_VALID)) continue;
    valid.push_back(i);
    valid_lo.push_back(lo[i]);
    valid_hi.push_back(hi[i]);
  }
  VvhPhotonMap map = build_vvh_photon_map(valid_lo, valid_hi, params.leaf_threshold);
  std::vector<uint32_t> sorted_slots(valid.size());
  std::vector<float4> sorted_lo(valid.size()), sorted_hi(valid.size());
  for (size_t k = 0; k < valid.size(); ++k) {
    sorted_slots[k] = valid[map.order[k]];
    sorted_lo[k] = valid_lo[map.order[k]];
    sorted_hi[k] = valid_hi[map.order[k]];
  }
  device_.upload(sort_.values, sorted_slots.data(), sorted_slots.size() * sizeof(uint32_t));
  device_.upload(owned(BufferSlot::map_lo), sorted_lo.data(), sorted_lo.size() * sizeof(float4));
  device_.upload(owned(BufferSlot::map_hi), sorted_hi.data(), sorted_hi.size() * sizeof(float4));
  device_.upload(owned(BufferSlot::map_nodes), map.nodes.data(), map.nodes.size() * sizeof(float4));
}

void PhotonPass::run_batch(LaunchParams params, PhotonStats* stats, StageTimer* timer) {
  const uint32_t slots = batch_size_ * slots_per_photon_;
  {
    StageScope scope(timer, Stage::photon_trace);
    device_.launch(KernelId::photon_trace, batch_size_, params);
  }
  // Bounds, count and footprint area: one small read-back per batch.
  const uint32_t tiles = (slots + PM_PHOTON_MAP_BOUNDS_TILE - 1) / PM_PHOTON_MAP_BOUNDS_TILE;
  std::vector<float4> partials(2 * size_t(tiles));
  {
    StageScope scope(timer, Stage::footprints);
    if (!(settings_.smoothing > 0))
      params.smoothing = batch_auto_smoothing(device_, owned(BufferSlot::footprint_partials), params, tiles, scene_area_);
    device_.launch(KernelId::photon_footprint, slots, params);
    device_.launch(KernelId::photon_reduce, tiles, params);
  }
  device_.download(owned(BufferSlot::footprint_partials), partials.data(), partials.size() * sizeof(float4));
  float4 lo{1e30f, 1e30f, 1e30f, 0}, hi{-1e30f, -1e30f, -1e30f, 0};
  double area = 0;
  uint64_t count = 0;
  for (uint32_t t = 0; t < tiles; ++t) {
    const float4& a = partials[2 * t];
    const float4& b = partials[2 * t + 1];
    lo = {std::min(lo.x, a.x), std::min(lo.y, a.y), std::min(lo.z, a.z), 0};
    hi = {std::max(hi.x, b.x), std::max(hi.y, b.y), std::max(hi.z, b.z), 0};
    area += a.w;
    uint32_t c;
    std::memcpy(&c, &b.w, 4);
    count += c;
  }
  const uint32_t threshold = settings_.leaf_threshold > 0
                                 ? uint32_t(settings_.leaf_threshold)
                                 : photon_map_auto_leaf_size(float(area), float(scene_area_), settings_.leaf_c);
  if (stats) {
    stats->hits += count;
    stats->footprint_area = area;
    stats->leaf_threshold = threshold;
    stats->smoothing = params.smoothing;
  }
  last_hit_count_ = uint32_t(count);
  map_params_.hit_count = 0;
  if (count == 0) return;  // every photon escaped or was absorbed before a recorded hit

  params.hit_bounds_lo = lo;
  params.hit_bounds_hi = hi;
  params.hit_count = uint32_t(count);
  params.leaf_threshold = threshold;
  device_.bind(BufferSlot::sort_keys, sort_.keys);
  device_.bind(BufferSlot::sort_values, sort_.values);
  if (settings_.vvh_map) {
    {
      StageScope scope(timer, Stage::map_tree);
      build_vvh_map(params);
      device_.launch(KernelId::photon_map_reorder, uint32_t(count), params);
    }
    map_params_ = params;
    gather(params, timer);
    return;
  }
  {
    StageScope scope(timer, Stage::map_morton);
    device_.launch(KernelId::photon_morton, slots, params);
  }
  {
    StageScope scope(timer, Stage::map_sort);
    device_.sort_pairs(sort_, slots, PM_MORTON_SORT_BITS);
  }
  device_.bind(BufferSlot::sort_keys, sort_.keys);  // the sort may hand back the other buffers
  device_.bind(BufferSlot::sort_values, sort_.values);
  {
    StageScope scope(timer, Stage::map_tree);
    if (count >= 2) device_.launch(KernelId::photon_map_nodes, uint32_t(count - 1), params);
    device_.launch(KernelId::photon_map_bottom_up, uint32_t(count), params);
    device_.launch(KernelId::photon_map_reorder, uint32_t(count), params);
  }
  map_params_ = params;
  gather(params, timer);
}

}  // namespace pm
