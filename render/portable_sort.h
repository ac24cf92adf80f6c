// Host driver of the portable radix sort kernels (kernels/common/radix_sort.h), used by backends
// without a library sort. Four bits per pass; the result ends in SortBuffers::keys/values.
#pragma once

#include "render/device.h"

namespace pm {

// Scratch the sort needs beyond the pair buffers: the digit histogram and chunk totals.
// Owned by the backend so repeated sorts reuse it.
class PortableSortScratch {
 public:
  DeviceBuffer& histogram(Device& device, uint32_t count);

 private:
  DeviceBuffer histogram_;
};

void portable_sort_pairs(Device& device, PortableSortScratch& scratch, SortBuffers& buffers, uint32_t count,
                         int key_bits);

}  // namespace pm
