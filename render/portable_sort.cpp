// Host driver of the portable radix sort: per digit of PM_SORT_RADIX_BITS, histogram (with the
// digits' and groups' totals) -> stable scatter, ping-ponging between the pair buffers (see
// kernels/common/radix_sort.h).
#include "render/portable_sort.h"

#include <algorithm>
#include <cstdint>
#include <utility>

namespace pm {

namespace {

uint32_t tile_count(uint32_t count) { return (count + PM_SORT_TILE - 1) / PM_SORT_TILE; }

// One set of totals: every digit's group totals, then the digit totals (radix_totals_size).
size_t totals_entries(uint32_t tiles) {
  return size_t(PM_SORT_RADIX) * ((tiles + PM_SORT_GROUP - 1) / PM_SORT_GROUP + 1);
}

// Digit counts, then two sets of totals (one per pass parity).
size_t histogram_bytes(uint32_t count) {
  return (size_t(PM_SORT_RADIX) * tile_count(count) + 2 * totals_entries(tile_count(count))) * sizeof(uint32_t);
}

}  // namespace

DeviceBuffer& PortableSortScratch::histogram(Device& device, uint32_t count) {
  size_t needed = histogram_bytes(count);
  if (histogram_.bytes() < needed) {
    histogram_.reset();  // free first: the old and the new need not fit together
    histogram_ = device.allocate(needed, "radix sort histogram");
  }
  return histogram_;
}

void portable_sort_pairs(Device& device, PortableSortScratch& scratch, DeviceBuffer& keys_in,
                         DeviceBuffer& values_in, DeviceBuffer& keys_out, DeviceBuffer& values_out, uint32_t count,
                         int key_bits) {
  const size_t bytes = size_t(count) * sizeof(uint32_t);
  if (count <= 1) {
    device.copy(keys_in, keys_out, bytes);
    device.copy(values_in, values_out, bytes);
    return;
  }
  LaunchParams params{};
  params.sort_count = count;
  params.sort_tile_count = tile_count(count);
  const uint32_t lanes = PM_SORT_RADIX * params.sort_tile_count;  // one per digit of every tile
  // Sized for as many pairs as the output has room for, so that passes whose counts vary within
  // that room do not grow it (device memory flat over passes).
  const uint32_t room = uint32_t(std::min<size_t>(keys_out.bytes() / sizeof(uint32_t), UINT32_MAX));
  DeviceBuffer& histogram = scratch.histogram(device, std::max(count, room));
  device.fill_zero(histogram, histogram_bytes(count));  // the first pass's totals; each scatter zeroes the next's
  device.bind(BufferSlot::sort_histogram, histogram);

  // Each pass scatters from (keys, values) into the other pair. With an even pass count the
  // input pair first goes to the output buffers, so that the last pass lands there.
  const int passes = (key_bits + PM_SORT_RADIX_BITS - 1) / PM_SORT_RADIX_BITS;
  DeviceBuffer* keys = &keys_in;
  DeviceBuffer* values = &values_in;
  DeviceBuffer* keys_alt = &keys_out;
  DeviceBuffer* values_alt = &values_out;
  if (passes % 2 == 0) {
    device.copy(keys_in, keys_out, bytes);
    device.copy(values_in, values_out, bytes);
    std::swap(keys, keys_alt);
    std::swap(values, values_alt);
  }
  for (int pass = 0; pass < passes; ++pass) {
    params.sort_shift = uint32_t(pass * PM_SORT_RADIX_BITS);
    device.bind(BufferSlot::sort_keys, *keys);
    device.bind(BufferSlot::sort_values, *values);
    device.bind(BufferSlot::sort_keys_alt, *keys_alt);
    device.bind(BufferSlot::sort_values_alt, *values_alt);
    device.launch(KernelId::sort_histogram, lanes, params);
    device.launch(KernelId::sort_scatter, lanes, params);
    std::swap(keys, keys_alt);
    std::swap(values, values_alt);
  }
  for (BufferSlot slot : {BufferSlot::sort_keys, BufferSlot::sort_values, BufferSlot::sort_keys_alt,
                          BufferSlot::sort_values_alt})
    device.unbind(slot);
}

}  // namespace pm
