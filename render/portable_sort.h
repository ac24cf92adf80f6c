// Host driver of the portable radix sort kernels (kernels/common/radix_sort.h), used by backends
// without a library sort. PM_SORT_RADIX_BITS per pass, ping-ponging between the input and output pairs.
#pragma once

#include "render/device.h"

namespace pm {

// Scratch the sort needs beyond the pair buffers: the digit counts and their totals.
// Owned by the backend so repeated sorts reuse it.
class PortableSortScratch {
 public:
  DeviceBuffer& histogram(Device& device, uint32_t count);

 private:
  DeviceBuffer histogram_;
};

// Device::sort_pairs for backends without a library sort: the sorted pairs end in
// keys_out/values_out; keys_in/values_in are used as the other half of each double buffer.
void portable_sort_pairs(Device& device, PortableSortScratch& scratch, DeviceBuffer& keys_in,
                         DeviceBuffer& values_in, DeviceBuffer& keys_out, DeviceBuffer& values_out, uint32_t count,
                         int key_bits);

}  // namespace pm
