// Gather against brute force, for any backend: after a real frame, every pixel's indirect and
// caustic radiance must equal the sum over ALL hits of the photon map (no BVH), evaluated on the
// host in double precision from the device's own map data. Catches traversal misses, wrong leaf
// fusion and kernel/BRDF/normalisation slips in the gather.
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "kernels/common/compat_host.h"
#include "kernels/common/brdf.h"
#include "kernels/common/camera_pass.h"
#include "kernels/common/footprint_clip.h"
#include "kernels/common/gather_reach.h"
#include "kernels/common/knn_gather.h"
#include "render/photon/photon_mapping.h"
#include "render/renderer.h"

namespace pm::test {

template <typename T>
std::vector<T> read_slot(Device& device, const Renderer& renderer, BufferSlot slot, size_t count) {
  std::vector<T> data(count);
  const DeviceBuffer& buffer = renderer.buffers()[slot];
  EXPECT_TRUE(bool(buffer)) << buffer_slot_name(slot);
  if (buffer && count) device.download(buffer, data.data(), count * sizeof(T));
  return data;
}

inline Vec3 v3(const float4& f) { return vec3(f.x, f.y, f.z); }
inline double dot3(const float4& a, Vec3 b) { return double(a.x) * b.x + double(a.y) * b.y + double(a.z) * b.z; }

inline PhotonSettings photon_settings(uint64_t photons, int estimator, int kernel, int leaf, int k) {
  PhotonSettings p;
  p.photons = photons;
  p.estimator = estimator;
  p.kernel_shape = kernel;
  p.leaf_threshold = leaf;
  p.knn_k = k;
  return p;
}

inline void check_gather_equals_brute_force(Device& device, const Scene& scene, PhotonSettings photons, int width,
                                            int height) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.mirror_depth = 1;
  settings.passes = 1;  // one pass: the map holds every hit
  settings.method = std::make_shared<PhotonSettings>(photons);
  // The device's own shading normals and positions, for the points of depth 0 (below).
  settings.layers = parse_film_layers("normal,position");
  Renderer renderer(device, scene, settings);
  renderer.render_frame(0);
  const auto* method = dynamic_cast<const PhotonMapping*>(renderer.method());
  ASSERT_NE(method, nullptr);
  const PhotonSettings& used = method->settings();
  const size_t n = method->last_hit_count();
  ASSERT_GT(n, 100u);
  auto center = read_slot<float4>(device, renderer, BufferSlot::map_center, n);
  auto row_u = read_slot<float4>(device, renderer, BufferSlot::map_row_u, n);
  auto row_v = read_slot<float4>(device, renderer, BufferSlot::map_row_v, n);
  auto row_n = read_slot<float4>(device, renderer, BufferSlot::map_row_n, n);
  auto cut = read_slot<float4>(device, renderer, BufferSlot::map_cut, n);
  auto power = read_slot<float4>(device, renderer, BufferSlot::map_power, n);
  auto incident = read_slot<float4>(device, renderer, BufferSlot::map_incident, n);
  const size_t pixels = size_t(width) * height, depths = size_t(renderer.mirror_depth()) + 1, records = depths * pixels;
  auto sp = read_slot<float2>(device, renderer, BufferSlot::shade_hit, records);
  auto indirect = read_slot<float4>(device, renderer, BufferSlot::film_indirect_sum, pixels);  // one pass: the sums are the image
  // A scene without mirrors makes no caustics, and its film keeps no caustic sum.
  auto caustic = renderer.has_caustic_film() ? read_slot<float4>(device, renderer, BufferSlot::film_caustic_sum, pixels)
                                             : std::vector<float4>(pixels, float4{0, 0, 0, 0});
  // A shading point's normal is its triangle's, and its position the camera ray's at its distance,
  // computed by each side in its own arithmetic: the device's fused multiply-adds and CUDA's fast
  // math may differ from the host's in the last bits, enough to change which footprint reaches a
  // point on its edge or which photon is knn's k-th. The brute force takes the device's normals
  // and positions where the layers have them (the first point of every pixel in a scene without
  // mirrors, as the scenes here are).
  auto device_normal = read_slot<float4>(device, renderer, BufferSlot::film_normal, pixels);
  auto device_position = read_slot<float4>(device, renderer, BufferSlot::film_position, pixels);
  std::vector<Material> materials = to_device_materials(scene);
  // knn's region (its clip at the walls and its covered area) is measured on the host by the
  // kernels' own function over the device's scene BVH; what is checked is the search and the sum.
  auto whole_slot = [&](BufferSlot slot) {
    return read_slot<float4>(device, renderer, slot, renderer.buffers()[slot].bytes() / sizeof(float4));
  };
  auto scene_nodes = whole_slot(BufferSlot::scene_nodes);
  auto triangles = whole_slot(BufferSlot::triangles);
  KernelGlobals scene_globals{};
  scene_globals.scene_nodes = scene_nodes.data();
  scene_globals.triangles = triangles.data();
  // The shading points' positions, directions towards the viewer and mirror weights, replayed as
  // the kernels replay them (eye_path_next).
  scene_globals.shade_hit = sp.data();
  scene_globals.materials = materials.data();
  const LaunchParams& gather_params = method->last_gather_params();
  const double region_stretch = 1.0 / std::pow(double(knn_region_thickness(&gather_params)), 2) - 1.0;

  double worst = 0;
  size_t nonzero = 0;
  for (size_t px = 0; px < pixels; ++px) {
    double sum[3] = {0, 0, 0};
    EyePath eye = eye_path_begin(uint(px));
    ShadingPoint point;
    while (eye_path_next(&scene_globals, &gather_params, &eye, &point)) {
      const size_t depth = eye.depth - 1;
      const Material& m = point.material;
      if (depth == 0 && renderer.mirror_depth() == 0) {
        point.normal = v3(device_normal[px]);
        point.position = v3(device_position[px]);
      }
      const Vec3 x = point.position, nrm = point.normal, wo = point.outgoing, weight = point.weight;
      std::vector<std::pair<double, size_t>> near;  // knn: (distance^2, index)
      for (size_t k = 0; k < n; ++k) {
        Vec3 d = vec3_sub(x, v3(center[k]));
        // The footprint (pd, radius) or reach (knn) on the hit's side of its cuts (the rows' w:
        // mu lu + mv lv <= t, and map_cut where flagged), and the photon's surface facing within
        // 60 degrees of the shading point's (gather_reach.h).
        double lu = dot3(row_u[k], d), lv = dot3(row_v[k], d), ln = dot3(row_n[k], d);
        double r2 = lu * lu + lv * lv + ln * ln;
        double facing = dot3(row_n[k], nrm), axis2 = dot3(row_n[k], v3(row_n[k]));
        bool second = (PM_AS_UINT(center[k].w) & PM_HIT_SECOND_CUT) != 0;
        bool reaches = r2 <= 1.0 && row_u[k].w * lu + row_v[k].w * lv <= row_n[k].w &&
                       (!second || cut[k].x * lu + cut[k].y * lv <= cut[k].z) && facing > 0 &&
                       facing * facing >= 0.25 * axis2;
        if (used.estimator == PM_ESTIMATOR_KNN) {
          // knn: in the region's metric (knn_gather.h), on a surface facing like x's.
          double h = double(d.x) * nrm.x + double(d.y) * nrm.y + double(d.z) * nrm.z;
          double d2 = double(d.x) * d.x + double(d.y) * d.y + double(d.z) * d.z + region_stretch * h * h;
          if (d2 < double(gather_params.rmax) * gather_params.rmax && facing > 0 && facing * facing >= 0.25 * axis2)
            near.push_back({d2, k});
          continue;
        }
        if (!reaches || vec3_dot(v3(incident[k]), nrm) <= 0.0f) continue;
        auto kernel = [&](double q2) {
          return q2 > 1.0 ? 0.0 : used.kernel_shape == PM_KERNEL_EPANECHNIKOV ? 2.0 * (1.0 - q2) : 1.0;
        };
        double w = kernel(r2);
        if (PM_AS_UINT(center[k].w) & PM_HIT_RIM) {
          // Folded at its rim m . q = t (map_cut, footprint_rim.h): the kernel at x's mirror image
          // q' = q - 2 (m . q - t) m across the rim as well, the normal coordinate unchanged. A
          // strip (map_cut's w, its width, > 0) also reflects across its far rim m . q = t - w:
          // every image that up to sixteen alternate reflections across the two reach, starting
          // with either rim.
          double s = cut[k].x * lu + cut[k].y * lv - cut[k].z;
          double qu = lu - 2.0 * s * cut[k].x, qv = lv - 2.0 * s * cut[k].y;
          w += kernel(qu * qu + qv * qv + ln * ln);
          if (cut[k].w > 0.0f) {
            const double near = cut[k].z, far = double(cut[k].z) - cut[k].w, along = s + cut[k].z;
            for (int first = 0; first < 2; ++first) {
              double image = along;
              for (int reflections = 1; reflections <= 16; ++reflections) {
                const double line = (reflections + first) % 2 ? near : far;
                image = 2.0 * line - image;
                if (reflections == 1 && first == 0) continue;  // the near rim's mirror, counted above
                const double du = (image - along) * cut[k].x, dv = (image - along) * cut[k].y;
                w += kernel((lu + du) * (lu + du) + (lv + dv) * (lv + dv) + ln * ln);
              }
            }
          }
        }
        // Divided by the kept kernel mass of the footprint moved to the shading point: each cut
        // line m . q <= t is t - m . (lu, lv) from it (gather_reach.h), floored as the gather floors it.
        float mu[2] = {row_u[k].w, second ? cut[k].x : 0.0f}, mv[2] = {row_v[k].w, second ? cut[k].y : 0.0f};
        float t[2] = {float(std::max(0.0, row_n[k].w - (mu[0] * lu + mv[0] * lv))),
                      second ? float(std::max(0.0, cut[k].z - (mu[1] * lu + mv[1] * lv))) : 1.0f};
        if (t[0] < 1.0f || t[1] < 1.0f)
          w /= std::max(double(footprint_kept_fraction(mu, mv, t, 2, used.kernel_shape)), double(PM_GATHER_MIN_KEPT));
        if (gather_params.facet_weighting) {
          // What the photon's beam delivers on x's surface over what it delivered on its own:
          // cos(wi, n) / cos(wi, n_hit), at most 4 (gather_reach.h).
          double own = dot3(incident[k], v3(row_n[k])) / std::sqrt(axis2), there = dot3(incident[k], nrm);
          w *= own > 0 && there > 0 ? std::min(there / own, double(PM_GATHER_MAX_TILT_GAIN)) : 0.0;
        }
        Vec3 f = brdf_eval(&m, nrm, v3(incident[k]), wo);
        sum[0] += weight.x * w * f.x * power[k].x;
        sum[1] += weight.y * w * f.y * power[k].y;
        sum[2] += weight.z * w * f.z * power[k].z;
      }
      if (used.estimator == PM_ESTIMATOR_KNN && !near.empty()) {
        std::sort(near.begin(), near.end());
        const size_t k_want = size_t(used.knn_k);
        const bool full = near.size() >= k_want;
        const double rmax = gather_params.rmax;
        const float radius = float(full ? std::sqrt(near[k_want - 1].first) : rmax);
        Footprint region;
        FootprintCut region_cut;
        const double area = knn_region_area(&scene_globals, &gather_params, x, nrm, radius,
                                            knn_region_turn(&gather_params, uint(px), uint(depth)), &region, &region_cut);
        // Of k photons within r, the k-th marks the radius and is not counted (knn_gather.h).
        for (size_t i = 0; i + (full ? 1 : 0) < std::min(near.size(), k_want); ++i) {
          size_t k = near[i].second;
          Vec3 d = vec3_sub(v3(center[k]), x);
          double lu = vec3_dot(region.axis_u, d) / vec3_dot(region.axis_u, region.axis_u);
          double lv = vec3_dot(region.axis_v, d) / vec3_dot(region.axis_v, region.axis_v);
          double ln = vec3_dot(region.axis_n, d) / vec3_dot(region.axis_n, region.axis_n);
          double r2 = lu * lu + lv * lv + ln * ln;
          if (r2 > 1.0 || !footprint_cut_keeps(&region_cut, float(lu), float(lv))) continue;
          if (vec3_dot(v3(incident[k]), nrm) <= 0.0f) continue;
          double w = used.kernel_shape == PM_KERNEL_EPANECHNIKOV ? 2.0 * (1.0 - r2) : 1.0;
          Vec3 f = brdf_eval(&m, nrm, v3(incident[k]), wo);
          double scale = w / area;
          sum[0] += weight.x * scale * f.x * power[k].x;
          sum[1] += weight.y * scale * f.y * power[k].y;
          sum[2] += weight.z * scale * f.z * power[k].z;
        }
      }
    }
    double got[3] = {double(indirect[px].x) + caustic[px].x, double(indirect[px].y) + caustic[px].y,
                     double(indirect[px].z) + caustic[px].z};
    for (int c = 0; c < 3; ++c) {
      double err = std::fabs(got[c] - sum[c]) / std::max(std::fabs(sum[c]), 1e-6);
      worst = std::max(worst, err);
      ASSERT_NEAR(got[c], sum[c], 2e-4 * std::fabs(sum[c]) + 1e-7) << "pixel " << px << " channel " << c;
      nonzero += sum[c] > 0;
    }
  }
  EXPECT_GT(nonzero, pixels);  // most pixels receive indirect light
  size_t rims = 0, strips = 0;  // footprints folded at one rim, and at a strip's two
  for (size_t k = 0; k < n; ++k)
    if (PM_AS_UINT(center[k].w) & PM_HIT_RIM) ++(cut[k].w > 0.0f ? strips : rims);
  std::printf("gather vs brute force over %zu hits (%zu folded at a rim, %zu at a strip's two): worst relative "
              "difference %.3g\n",
              n, rims, strips, worst);
}

}  // namespace pm::test
