// Orchestration of the photon stages, pass by pass, over the Device interface and the buffer
// table's photon group.
#include "render/photon/photon_mapping.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <numeric>

#include "kernels/common/photon_map.h"
#include "kernels/common/pixel_order.h"
#include "render/errors.h"
#include "render/footprint_scale.h"
#include "render/photon/vvh_builder.h"
#include "render/scene_emitters.h"
#include "render/scene_environment.h"

namespace pm {

std::vector<uint32_t> share_photons_by_power(const std::vector<LightDesc>& lights, uint32_t total, double area_power,
                                             double environment_power) {
  std::vector<double> power;
  for (const LightDesc& l : lights)
    power.push_back((double(l.power.x) + l.power.y + l.power.z) * light_emitted_fraction(l));
  if (area_power > 0) power.push_back(area_power);
  if (environment_power > 0) power.push_back(environment_power);
  const double sum = std::accumulate(power.begin(), power.end(), 0.0);
  std::vector<uint32_t> share(power.size(), 0);
  if (sum <= 0) return share;
  std::vector<std::pair<double, size_t>> remainders;
  uint32_t given = 0;
  for (size_t i = 0; i < power.size(); ++i) {
    const double exact = total * power[i] / sum;
    share[i] = uint32_t(std::floor(exact));
    given += share[i];
    remainders.push_back({exact - share[i], i});
  }
  std::sort(remainders.rbegin(), remainders.rend());
  for (size_t k = 0; given < total && k < remainders.size(); ++k, ++given) share[remainders[k].second]++;
  return share;
}

// S3 over the sorted hits (kernels/common/footprint_probes.h): the footprints, their coverage with
// a work item per probe (in launches of at most 2^31 items; on devices without lockstep lanes a
// work item per footprint), the fit of the footprints at edges, then the gather data. The records'
// counter, read since the trace, counts the footprints at edges.
static void launch_footprints(Device& device, DeviceBuffer& counter, LaunchParams params, uint32_t hits) {
  device.launch(KernelId::photon_footprint, hits, params);
  if (params.footprint_coverage && params.estimator != PM_ESTIMATOR_KNN) {
    const uint32_t zero = 0;  // the list of footprints at edges starts empty
    device.upload(counter, &zero, sizeof(zero));
    if (device.info().lockstep_lanes) {
      const uint32_t hits_per_launch = (1u << 31) / PM_FOOTPRINT_PROBES;
      for (const KernelId probes : {KernelId::photon_footprint_probe, KernelId::photon_footprint_edge_probe}) {
        for (uint32_t first = 0; first < hits; first += hits_per_launch) {
          params.batch_first = first;
          device.launch(probes, std::min(hits - first, hits_per_launch) * PM_FOOTPRINT_PROBES, params);
        }
        if (probes == KernelId::photon_footprint_probe) device.launch(KernelId::photon_footprint_pattern, hits, params);
      }
    } else {
      device.launch(KernelId::photon_footprint_coverage, hits, params);
    }
    params.batch_first = 0;
    device.launch(KernelId::photon_footprint_rim, hits, params);
  }
  device.launch(KernelId::photon_footprint_store, hits, params);
}

PhotonMapping::PhotonMapping(const MethodContext& context, const PhotonSettings& settings)
    : device_(context.device),
      buffers_(context.buffers),
      settings_(settings.resolved(context.measures)),
      growth_promise_(context.device) {
  settings_.validate();
  scene_area_ = context.measures.surface_area;
  photons_first_ = uint32_t(settings_.photons_in_pass(0));
  photons_most_ = uint32_t(settings_.photons_max_or_default());
  slots_per_photon_ = settings_.hit_slots_per_photon(context.scene.has_mirrors());
  shading_points_ = context.shading_points;
  planned_passes_ = std::max(context.planned_passes, 1u);
  extents_.hit_slots = hit_slots();
  extents_.bounds_tiles = (extents_.hit_slots + PM_PHOTON_MAP_BOUNDS_TILE - 1) / PM_PHOTON_MAP_BOUNDS_TILE;
  // Tiles walk the map together where lanes run in lockstep (kernels/common/gather_tiles.h); the
  // knn gather and final gathering read the map at points of their own.
  const float tile_gather = settings_.tile_gather != PhotonSettings::kTileGatherAuto ? settings_.tile_gather
                            : device_.info().lockstep_lanes                          ? kTileGatherReach
                                                                                     : 0.0f;
  const bool tiles_apply = settings_.estimator != PM_ESTIMATOR_KNN && settings_.final_gather == 0;
  tile_gather_ = tiles_apply ? tile_gather : 0.0f;
  // T_auto's bounds for how the map is walked on GPUs (photon_map_leaf_size_within): the tiles'
  // wherever tiles walk by default, whether or not this run's do, so that `--tile-gather` leaves the
  // image's bits as they are; final gathering's at its rays' hits.
  if (device_.info().lockstep_lanes && tiles_apply) {
    leaf_least_ = PM_TILE_WALK_LEAF_MIN;
    leaf_most_ = PM_TILE_WALK_LEAF_MAX;
  } else if (device_.info().lockstep_lanes && settings_.final_gather > 0) {
    leaf_least_ = PM_RAY_HIT_WALK_LEAF_MIN;
  }
  gather_tiles_ = pixel_work_items(uint32_t(context.width), uint32_t(context.height)) / (PM_TILE_W * PM_TILE_H);
  extents_.gather_tiles = tile_gather_ > 0 ? gather_tiles_ : 0;
  // The hit records start with room for half as many hits as photons (Sponza and Sibenik record
  // about that many); a first pass that records more traces again with room for what it recorded
  // (room_for: its noise, no margin for change yet), so the room ends near the hits a pass
  // records, not at a guess above them. The map is allocated by the first pass, for the hits it
  // records (reserve_map). Until they grow, the memory checks count both at the room of 5/4 of
  // the photons' hits.
  extents_.hit_records = std::min<uint64_t>(uint64_t(photons_first_) / 2, hit_slots());
  resize_growing_buffers();
  area_power_ = build_scene_emitters(context.scene).power_rgb_sum;
  environment_power_ = environment_power_rgb_sum(context.scene.environment, context.measures);
  share_photons(context.scene.lights, photons_first_);
}

void PhotonMapping::share_photons(const std::vector<LightDesc>& lights, uint32_t photons) {
  photons_shared_ = photons;
  const std::vector<uint32_t> counts = share_photons_by_power(lights, photons, area_power_, environment_power_);
  std::vector<uint4> emitters(std::max<size_t>(counts.size(), 1), uint4{0, 0, 0, 0});
  uint32_t first = 0;
  for (size_t i = 0; i < counts.size(); ++i) {
    emitters[i] = uint4{first, counts[i], 0, 0};
    first += counts[i];
  }
  buffers_.upload(BufferSlot::photon_emitters, emitters);
  buffers_.bind_all();  // the upload may have reallocated the buffer
}

std::vector<StageInfo> PhotonMapping::stages(const FrameContext& frame) const {
  // Per frame, as the stage timer sums a frame's passes: the photons of its planned passes.
  const double photons = double(settings_.photons_before_pass(planned_passes_));
  const char* emitted = "photons emitted per frame";
  std::vector<StageInfo> list;
  for (const char* stage : {"photon trace", "map: morton", "map: sort", "footprints", "map: tree"})
    list.push_back({stage, photons, "photons/s", emitted});
  list.push_back({settings_.final_gather > 0 ? "final gather" : "gather",
                  stats_.get("shading_points", double(shading_points_)) * planned_passes_, "shading points/s",
                  "shading points gathered per frame, every pass"});
  return list;
}

LaunchParams PhotonMapping::pass_params(const FrameContext& frame, uint32_t pass) const {
  LaunchParams params = frame.params;
  // Photon i of pass k is photon (the photons of passes 0..k-1) + i of the frame: its random
  // stream (a 64-bit index).
  const uint64_t first = settings_.photons_before_pass(pass);
  params.photon_count = uint32_t(settings_.photons_in_pass(pass));
  params.photon_offset = uint32_t(first);
  params.photon_offset_hi = uint32_t(first >> 32);
  params.footprint_scale = float(settings_.footprint_scale(pass));
  params.photon_frame = uint32_t(photon_frame_);
  params.hit_slots_per_photon = slots_per_photon_;
  // Final gathering reads the map one bounce from the shading point: its photons carry one bounce
  // fewer (final_gather.h).
  params.max_bounces = uint32_t(settings_.bounces) - (settings_.final_gather > 0 ? 1u : 0u);
  params.final_gather_rays = settings_.final_gather;
  params.smoothing = settings_.smoothing;
  // k-NN has no footprints: the shrink bounds its search radius instead.
  params.rmax = settings_.estimator == PM_ESTIMATOR_KNN ? float(settings_.rmax * params.footprint_scale) : settings_.rmax;
  params.gather_radius = settings_.radius;
  params.knn_k = uint32_t(settings_.knn_k);
  params.estimator = uint32_t(settings_.estimator);
  params.kernel_shape = uint32_t(settings_.kernel_shape);
  params.footprint_clip = settings_.footprint_clip ? 1u : 0u;
  params.footprint_coverage = settings_.footprint_coverage ? 1u : 0u;
  params.facet_weighting = settings_.facet_weighting == 1 && settings_.estimator != PM_ESTIMATOR_KNN ? 1u : 0u;
  params.footprint_thickness = settings_.footprint_thickness;
  params.photon_sequence = uint32_t(settings_.sequence);
  return params;
}

void PhotonMapping::begin_frame(const FrameContext& frame, const FrameChange& change) {
  if (change.lights) {
    map_intact_ = false;
    share_photons(*frame.lights, photons_first_);
  }
  // Camera-only frames reuse the photons of their run's first frame; Halton photons do not
  // depend on the frame at all (types.h).
  if (settings_.sequence == PM_PHOTON_SEQUENCE_HALTON) photon_frame_ = 0;
  else photon_frame_ = frame.reuse_lighting ? frame.light_run_start : frame.frame;
  stats_ = MethodStats{};
  stats_.set("photon_frame", photon_frame_);
  stats_.set("photons_reused", 0);
  stats_.set("photons_per_pass", photons_first_);
  stats_.set("hits", 0);
  // The tiles' boxes of this frame's shading points, for every pass's gather.
  if (tile_gather_ > 0 && photons_first_ > 0) {
    StageScope scope(frame.timer, "gather");
    device_.launch(KernelId::gather_tile_bounds, gather_tiles_, frame.params);
  }
}

void PhotonMapping::run_pass(const FrameContext& frame, uint32_t pass) {
  if (photons_first_ == 0) return;
  LaunchParams params = pass_params(frame, pass);
  // Final gathering's passes grow (PhotonSettings::photons_in_pass): the lights' shares follow.
  if (params.photon_count != photons_shared_) share_photons(*frame.lights, params.photon_count);
  const bool reuse = frame.reuse_lighting && map_intact_ && map_photon_frame_ == photon_frame_ && map_pass_ == pass;
  uint32_t* counters = nullptr;
  uint32_t counts[3] = {0, 0, 0};
  if (frame.collect_stats) {
    device_.fill_zero(buffers_[BufferSlot::gather_stats], buffers_[BufferSlot::gather_stats].bytes());
    counters = counts;
  }
  if (reuse) {
    params.hit_bounds_lo = map_params_.hit_bounds_lo;
    params.hit_bounds_hi = map_params_.hit_bounds_hi;
    params.hit_count = map_params_.hit_count;
    params.leaf_threshold = map_params_.leaf_threshold;
    map_intact_ = false;  // until this gather has gone through
    if (params.hit_count > 0 || settings_.final_gather > 0) gather(params, frame.timer);
    map_intact_ = true;
    stats_.set("photons_reused", 1);
  } else {
    map_intact_ = false;
    trace_and_build(params, frame.timer);
    // A final gather reads the direct light at its rays' hits even where the map is empty.
    if (map_params_.hit_count > 0 || settings_.final_gather > 0) gather(map_params_, frame.timer);
    map_intact_ = true;
    map_photon_frame_ = photon_frame_;
    map_pass_ = pass;
  }
  stats_.set("hits", stats_.get("hits") + map_params_.hit_count);
  stats_.set("photons_per_pass", params.photon_count);
  stats_.set("footprint_area", map_footprint_area_);
  stats_.set("leaf_threshold", map_params_.leaf_threshold);
  stats_.set("smoothing", map_smoothing_);
  if (counters) {
    device_.download(buffers_[BufferSlot::gather_stats], counters, sizeof(counts));
    stats_.set("gathered", stats_.get("gathered") + counts[0]);
    stats_.set("shading_points", counts[1]);
    stats_.set("photons_per_gather", counts[1] ? stats_.get("gathered") / ((pass + 1.0) * counts[1]) : 0.0);
    // The share of shading points whose tile walked the map together (kernels/common/gather_tiles.h).
    if (tile_gather_ > 0) stats_.set("tile_walked_share", counts[1] ? double(counts[2]) / counts[1] : 0.0);
  }
}

void PhotonMapping::gather(const LaunchParams& params, StageTimer* timer) {
  StageScope scope(timer, settings_.final_gather > 0 ? "final gather" : "gather");
  KernelId gather = settings_.estimator == PM_ESTIMATOR_KNN ? KernelId::knn_gather
                    : params.facet_weighting  ? KernelId::facet_gather
                                              : KernelId::gather;
  if (settings_.final_gather > 0) gather = KernelId::final_gather;
  LaunchParams launch = params;
  // A tile's reach: tile_gather_ of this pass's mean footprint radii (the footprints' total area
  // over their count, as discs).
  if (tile_gather_ > 0 && params.hit_count > 0)
    launch.tile_gather_reach =
        float(tile_gather_ * std::sqrt(map_footprint_area_ / (double(params.hit_count) * PM_PI)));
  device_.launch(gather, pixel_work_items(params.width, params.height), launch);
}

uint64_t PhotonMapping::growing_bytes(uint64_t map_hits, uint64_t hit_records) const {
  BufferExtents with = extents_, without = extents_;
  with.map_hits = map_hits;
  with.hit_records = hit_records;
  without.map_hits = without.hit_records = 0;
  return buffer_group_bytes(BufferGroup::photon, with) - buffer_group_bytes(BufferGroup::photon, without);
}

uint32_t PhotonMapping::expected_most_hits() const {
  return uint32_t(std::min<uint64_t>(uint64_t(photons_most_) * 5 / 4, hit_slots()));
}

MethodWork PhotonMapping::work(uint32_t passes) const {
  const double largest = passes > 0 ? double(settings_.photons_in_pass(passes - 1)) : 0.0;
  return {"photon", double(settings_.photons_before_pass(passes)), largest};
}

uint64_t hit_room(uint64_t hits, bool changing) {
  return hits + (changing ? hits / 16 : 0) + uint64_t(std::ceil(8.0 * std::sqrt(double(hits))));
}

uint32_t PhotonMapping::room_for(uint32_t hits) const {
  // No more than the checks counted while the hits fit in it. Sized by the hits, not the
  // photons: most photons of a pass record fewer hits than their slots (Sponza about one valid
  // hit per two photons, docs/benchmarks.md).
  uint64_t room = hit_room(hits, hits_measured_);
  if (hits <= expected_most_hits()) room = std::min<uint64_t>(room, expected_most_hits());
  return uint32_t(std::min<uint64_t>(room, hit_slots()));
}

void PhotonMapping::resize_growing_buffers() {
  buffers_.allocate(BufferGroup::photon, extents_);
  buffers_.bind_all();
  const uint64_t held = growing_bytes(extents_.map_hits, extents_.hit_records);
  const uint64_t expected = growing_bytes(expected_most_hits(), expected_most_hits());
  growth_promise_.set(expected > held ? expected - held : 0);
}

void PhotonMapping::reserve_map(uint32_t hits) {
  if (hits <= extents_.map_hits) return;
  extents_.map_hits = room_for(hits);
  resize_growing_buffers();
}

void PhotonMapping::reserve_hit_records(uint32_t hits) {
  if (hits <= extents_.hit_records) return;
  extents_.hit_records = room_for(hits);
  resize_growing_buffers();
}

// The VVH alternative to the device LBVH: the hits' footprints, computed in slot order, go to
// the host; the tree comes back in the same node layout with its own hit order, into which the
// gather data is permuted, so the gather runs unchanged.
void PhotonMapping::build_vvh_map(const LaunchParams& params) {
  const uint32_t n = params.hit_count;
  std::vector<float4> lo(n), hi(n);
  device_.download(buffers_[BufferSlot::map_lo], lo.data(), n * sizeof(float4));
  device_.download(buffers_[BufferSlot::map_hi], hi.data(), n * sizeof(float4));
  VvhPhotonMap map = build_vvh_photon_map(lo, hi, params.leaf_threshold);
  for (BufferSlot slot : {BufferSlot::map_lo, BufferSlot::map_hi, BufferSlot::map_center, BufferSlot::map_row_u,
                          BufferSlot::map_row_v, BufferSlot::map_row_n, BufferSlot::map_power, BufferSlot::map_incident,
                          BufferSlot::map_cut}) {
    std::vector<float4> data(n), permuted(n);
    device_.download(buffers_[slot], data.data(), n * sizeof(float4));
    for (uint32_t k = 0; k < n; ++k) permuted[k] = data[map.order[k]];
    device_.upload(buffers_[slot], permuted.data(), n * sizeof(float4));
  }
  // The nodes take the hit records' memory (PM_MAP_NODES, kernels/common/buffers.h): n - 1 inner
  // nodes for n hits fit there; the records are spent by now, so the room may grow without loss.
  reserve_hit_records(uint32_t((map.nodes.size() + PM_RECORD_FLOAT4S - 1) / PM_RECORD_FLOAT4S));
  device_.upload(buffers_[BufferSlot::hit_records], map.nodes.data(), map.nodes.size() * sizeof(float4));
}

// S1-S4 for one pass: leaves the photon map and its parameters in map_params_.
void PhotonMapping::trace_and_build(LaunchParams params, StageTimer* timer) {
  const uint32_t tiles = photon_map_bounds_tile_count(params.photon_count * slots_per_photon_);
  std::vector<float4> partials(2 * size_t(tiles));
  PhotonMapBounds bounds;
  const LaunchParams traced = params;
  // A pass with more photons than the last: records in proportion to what those took.
  if (last_traced_photons_ > 0 && params.photon_count > last_traced_photons_)
    reserve_hit_records(uint32_t(std::min<uint64_t>(
        uint64_t(last_records_) * params.photon_count / last_traced_photons_, hit_slots())));
  for (;;) {
    // The records' counter and room (photon_trace.h), then the trace.
    const uint32_t counter[2] = {0, uint32_t(extents_.hit_records)};
    device_.upload(buffers_[BufferSlot::hit_record_count], counter, sizeof(counter));
    {
      StageScope scope(timer, "photon trace");
      device_.launch(KernelId::photon_trace, traced.photon_count, traced);
    }
    if (!(settings_.smoothing > 0)) {
      StageScope scope(timer, "footprints");
      params.smoothing =
          batch_auto_smoothing(device_, buffers_[BufferSlot::map_partials], traced, scene_area_, settings_.overlap);
    }
    // Bounds and count of the valid hits, per tile, and the records the trace took: one small
    // read-back per pass.
    uint32_t records[2] = {0, 0};
    {
      StageScope scope(timer, "map: morton");
      device_.launch(KernelId::photon_reduce, tiles, traced);
      device_.download(buffers_[BufferSlot::map_partials], partials.data(), partials.size() * sizeof(float4));
      device_.download(buffers_[BufferSlot::hit_record_count], records, sizeof(records));
      bounds = photon_map_combine_partials(partials.data(), tiles);
    }
    last_records_ = records[0];
    last_traced_photons_ = traced.photon_count;
    if (records[0] <= extents_.hit_records) break;
    // More hits than the records had room for: the same photons again, with room for them.
    reserve_hit_records(records[0]);
  }
  params.hit_bounds_lo = bounds.lo;
  params.hit_bounds_hi = bounds.hi;
  params.hit_count = bounds.count;
  map_smoothing_ = params.smoothing;
  map_footprint_area_ = 0;
  map_params_ = params;
  if (bounds.count > 0) reserve_map(bounds.count);
  hits_measured_ = true;  // the rooms now hold a pass's hits: growing past them means the hits change
  if (bounds.count == 0) return;  // every photon escaped or was absorbed before a recorded hit

  // The valid hits' Morton keys, compacted at each tile's offset, sorted (VVH: kept in slot order).
  {
    StageScope scope(timer, "map: morton");
    std::vector<uint32_t> first_out(tiles);
    photon_map_tile_offsets(partials.data(), tiles, first_out.data());
    device_.upload(buffers_[BufferSlot::map_tile_offsets], first_out.data(), tiles * sizeof(uint32_t));
    device_.launch(KernelId::photon_morton, tiles, params);
  }
  {
    StageScope scope(timer, "map: sort");
    if (settings_.builder == kPhotonMapVvh)
      device_.copy(buffers_[BufferSlot::PM_SORT_SLOTS_BUFFER], buffers_[BufferSlot::sorted_slots],
                   bounds.count * sizeof(uint32_t));
    else  // the input pairs live in gather arrays the footprints write next (PM_SORT_KEYS, buffers.h)
      device_.sort_pairs(buffers_[BufferSlot::PM_SORT_KEYS_BUFFER], buffers_[BufferSlot::PM_SORT_SLOTS_BUFFER],
                         buffers_[BufferSlot::sorted_keys], buffers_[BufferSlot::sorted_slots], bounds.count,
                         PM_MORTON_SORT_BITS);
  }
  // S3 in sorted order, then the footprints' total area for T_auto.
  const uint32_t map_tiles = photon_map_bounds_tile_count(bounds.count);
  {
    StageScope scope(timer, "footprints");
    launch_footprints(device_, buffers_[BufferSlot::hit_record_count], params, bounds.count);
    device_.launch(KernelId::photon_map_area, map_tiles, params);
  }
  device_.download(buffers_[BufferSlot::map_partials], partials.data(), 2 * size_t(map_tiles) * sizeof(float4));
  map_footprint_area_ = photon_map_combine_partials(partials.data(), map_tiles).area;
  if (settings_.leaf_threshold > 0) {
    params.leaf_threshold = uint32_t(settings_.leaf_threshold);
  } else {
    params.leaf_threshold = photon_map_auto_leaf_size(float(map_footprint_area_), float(scene_area_), settings_.leaf_c);
    params.leaf_threshold = photon_map_leaf_size_within(params.leaf_threshold, leaf_least_, leaf_most_);
  }
  map_params_ = params;
  StageScope scope(timer, "map: tree");
  if (settings_.builder == kPhotonMapVvh) {
    build_vvh_map(params);
    return;
  }
  if (bounds.count >= 2) device_.launch(KernelId::photon_map_nodes, bounds.count - 1, params);
  device_.launch(KernelId::photon_map_bottom_up, bounds.count, params);
}

}  // namespace pm
