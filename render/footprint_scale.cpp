// Automatic smoothing factor per photon batch (render/footprint_scale.h).
#include "render/footprint_scale.h"

#include "kernels/common/compat_host.h"
#include "kernels/common/footprint_scale.h"

#include <cmath>
#include <cstring>
#include <vector>

namespace pm {

float auto_smoothing(double area_at_s1, double scene_area, double overlap) {
  if (!(area_at_s1 > 0) || !std::isfinite(area_at_s1) || !(scene_area > 0)) return 1.0f;
  const double s = std::sqrt(overlap * scene_area / area_at_s1);
  return std::isfinite(s) && s > 0 ? float(s) : 1.0f;
}

double footprint_scale_tile_sum(const float* tile_sums, uint32_t tiles) {
  double area = 0;  // in tile order: the same sum whatever runs the tiles
  for (uint32_t t = 0; t < tiles; ++t) area += tile_sums[t];
  return area;
}

float batch_auto_smoothing(Device& device, const DeviceBuffer& partials, const LaunchParams& params,
                           double scene_area, double overlap, double* area_at_s1) {
  const uint32_t tiles = footprint_scale_tile_count(params.photon_count * params.hit_slots_per_photon);
  device.launch(KernelId::photon_footprint_scale, tiles, params);
  std::vector<float> tile_sums(tiles);
  device.download(partials, tile_sums.data(), tile_sums.size() * sizeof(float));
  const double area = footprint_scale_tile_sum(tile_sums.data(), tiles);
  if (area_at_s1) *area_at_s1 = area;
  return auto_smoothing(area, scene_area, overlap);
}

}  // namespace pm
