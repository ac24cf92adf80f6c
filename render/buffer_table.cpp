// Buffer table: per-slot group, element size and extent generated from PM_BUFFER_LIST, and the
// allocation, binding and accounting that follow from them.
#include "render/buffer_table.h"

#include <string>

namespace pm {

namespace {

struct SlotLayout {
  BufferGroup group;
  size_t element_bytes;
  uint64_t BufferExtents::*extent;
  uint64_t per;
};

const SlotLayout kLayout[] = {
#define PM_SLOT_LAYOUT(group, type, name, extent, per) {BufferGroup::group, sizeof(type), &BufferExtents::extent, per},
    PM_BUFFER_LIST(PM_SLOT_LAYOUT)
#undef PM_SLOT_LAYOUT
};
static_assert(sizeof(kLayout) / sizeof(kLayout[0]) == kBufferSlotCount, "one layout per buffer slot");

const SlotLayout& layout(size_t slot) { return kLayout[slot]; }

bool bound_by_renderer(BufferGroup group) { return group != BufferGroup::backend && group != BufferGroup::test; }

uint64_t slot_bytes(size_t slot, const BufferExtents& extents) {
  const SlotLayout& l = layout(slot);
  return extents.*l.extent * l.per * l.element_bytes;
}

}  // namespace

BufferGroup buffer_group(BufferSlot slot) { return layout(static_cast<size_t>(slot)).group; }

size_t buffer_element_bytes(BufferSlot slot) { return layout(static_cast<size_t>(slot)).element_bytes; }

uint64_t buffer_group_bytes(BufferGroup group, const BufferExtents& extents) {
  uint64_t total = 0;
  for (size_t s = 0; s < kBufferSlotCount; ++s)
    if (layout(s).group == group && layout(s).extent != &BufferExtents::uploaded) total += slot_bytes(s, extents);
  return total;
}

void BufferTable::allocate(BufferGroup group, const BufferExtents& extents) {
  for (size_t s = 0; s < kBufferSlotCount; ++s) {
    if (layout(s).group != group || layout(s).extent == &BufferExtents::uploaded) continue;
    const uint64_t bytes = slot_bytes(s, extents);
    DeviceBuffer& buffer = buffers_[s];
    if (bytes == buffer.bytes() && (bytes == 0 || buffer)) continue;
    buffer.reset();  // free first: the old and the new buffer need not fit together
    if (bytes > 0) buffer = device_.allocate(bytes, buffer_slot_name(static_cast<BufferSlot>(s)));
  }
}

void BufferTable::release(BufferGroup group) {
  for (size_t s = 0; s < kBufferSlotCount; ++s)
    if (layout(s).group == group) buffers_[s].reset();
}

void BufferTable::upload(BufferSlot slot, const void* data, size_t bytes) {
  DeviceBuffer& buffer = (*this)[slot];
  if (!buffer || buffer.bytes() < bytes) {
    buffer.reset();
    buffer = device_.allocate(bytes, buffer_slot_name(slot));
  }
  device_.upload(buffer, data, bytes);
}

void BufferTable::copy_from(BufferSlot slot, const DeviceBuffer& source) {
  DeviceBuffer& buffer = (*this)[slot];
  buffer.reset();
  if (!source || source.bytes() == 0) return;
  buffer = device_.allocate(source.bytes(), buffer_slot_name(slot));
  device_.copy(source, buffer, source.bytes());
}

void BufferTable::bind_all() const {
  for (size_t s = 0; s < kBufferSlotCount; ++s) {
    if (!bound_by_renderer(layout(s).group)) continue;
    const BufferSlot slot = static_cast<BufferSlot>(s);
    if (buffers_[s]) device_.bind(slot, buffers_[s]);
    else device_.unbind(slot);
  }
}

uint64_t BufferTable::bytes() const {
  uint64_t total = 0;
  for (const DeviceBuffer& b : buffers_) total += b.bytes();
  return total;
}

uint64_t BufferTable::bytes(BufferGroup group) const {
  uint64_t total = 0;
  for (size_t s = 0; s < kBufferSlotCount; ++s)
    if (layout(s).group == group) total += buffers_[s].bytes();
  return total;
}

}  // namespace pm
