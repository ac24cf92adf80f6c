// Footprint radii of the photon map on the device, binned as the paper's Table 3 (0.05 m wide bins
// from 0 to 1.00, then "> 1.00"): what `pmrender bench --radius-histogram` prints.
#pragma once

#include <array>
#include <cstdint>
#include <string>

#include "render/buffer_table.h"

namespace pm {

struct FootprintHistogram {
  static constexpr int kBins = 20;            // then one more: > kBins * kBinWidth
  static constexpr double kBinWidth = 0.05;   // metres
  std::array<uint64_t, kBins + 1> bins{};
  uint64_t valid = 0;       // valid hits
  uint64_t degenerate = 0;  // valid hits with zero footprint area (not binned)
  double max_radius = 0;

  static std::string bin_label(int bin);  // "0.00 - 0.05", ..., "> 1.00"
};

// Radii sqrt(area / pi) of the `hits` footprints the photon map holds now (the last pass).
FootprintHistogram footprint_radius_histogram(Device& device, const BufferTable& buffers, uint32_t hits);

}  // namespace pm
