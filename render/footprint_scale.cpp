// Automatic smoothing factor per photon batch (render/footprint_scale.h).
#include "render/footprint_scale.h"

#include <cmath>
#include <cstring>
#include <vector>

namespace pm {

float auto_smoothing(double area_at_s1, double scene_area, double overlap) {
  if (!(area_at_s1 > 0) || !std::isfinite(area_at_s1) || !(scene_area > 0)) return 1.0f;
  const double s = std::sqrt(overlap * scene_area / area_at_s1);
  return std::isfinite(s) && s > 0 ? float(s) : 1.0f;
}

float batch_auto_smoothing(Device& device, const DeviceBuffer& partials, const LaunchParams& params, uint32_t tiles,
                           double scene_area, double overlap, double* area_at_s1) {
  device.launch(KernelId::photon_footprint_scale, tiles, params);
  std::vector<float4> tile_sums(2 * size_t(tiles));
  device.download(partials, tile_sums.data(), tile_sums.size() * sizeof(float4));
  double area = 0;  // in tile order: the same sum whatever runs the tiles
  for (uint32_t t = 0; t < tiles; ++t) area += tile_sums[2 * size_t(t)].x;
  if (area_at_s1) *area_at_s1 = area;
  return auto_smoothing(area, scene_area, overlap);
}

}  // namespace pm
