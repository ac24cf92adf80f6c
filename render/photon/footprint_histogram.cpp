// Footprint radius histogram from the photon map's buffers (area in map_lo.w, flags in
// map_center.w; kernels/common/buffers.h).
#include "render/photon/footprint_histogram.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

#include "render/errors.h"

namespace pm {

std::string FootprintHistogram::bin_label(int bin) {
  char text[32];
  if (bin == kBins) std::snprintf(text, sizeof(text), "> %.2f", kBins * kBinWidth);
  else std::snprintf(text, sizeof(text), "%.2f - %.2f", bin * kBinWidth, (bin + 1) * kBinWidth);
  return text;
}

FootprintHistogram footprint_radius_histogram(Device& device, const BufferTable& buffers, uint32_t hits) {
  const DeviceBuffer& lo = buffers[BufferSlot::map_lo];
  const DeviceBuffer& center = buffers[BufferSlot::map_center];
  if (!lo || !center) throw DeviceError("footprint histogram: no photon footprints on the device");
  const size_t slots = std::min<size_t>(hits, std::min(lo.bytes(), center.bytes()) / sizeof(float4));
  std::vector<float4> areas(slots), flags(slots);
  device.download(lo, areas.data(), slots * sizeof(float4));
  device.download(center, flags.data(), slots * sizeof(float4));
  FootprintHistogram h;
  for (size_t i = 0; i < slots; ++i) {
    uint32_t bits;
    std::memcpy(&bits, &flags[i].w, sizeof(bits));
    if ((bits & PM_HIT_VALID) == 0) continue;
    ++h.valid;
    const double area = areas[i].w;
    if (!(area > 0)) {
      ++h.degenerate;
      continue;
    }
    const double r = std::sqrt(area / double(PM_PI));
    h.max_radius = std::max(h.max_radius, r);
    const int bin = r > FootprintHistogram::kBins * FootprintHistogram::kBinWidth
                        ? FootprintHistogram::kBins
                        : std::min(FootprintHistogram::kBins - 1, int(r / FootprintHistogram::kBinWidth));
    ++h.bins[size_t(bin)];
  }
  return h;
}

}  // namespace pm
