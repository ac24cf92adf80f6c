// The one host object that allocates, binds, resizes and frees every device buffer of a
// renderer, generated from PM_BUFFER_LIST (kernels/common/buffers.h): each buffer's group says
// who owns it and when it lives, its extent and multiplier how many elements it holds. A method
// allocates its group once for its pass size; the renderer binds the whole table once per frame.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "render/device.h"

namespace pm {

// The owners of buffers, as the first column of PM_BUFFER_LIST names them.
enum class BufferGroup : int {
  scene,    // uploaded once per renderer
  frame,    // sized by the resolution: shading points and film
  photon,   // the photon-mapping method, sized by its photons per pass
  radiosity,  // the vertex link radiosity method, sized by its elements and link batch
  backend,  // scratch a backend binds itself (the portable sort)
  test,     // bound by tests only
};

// Element counts the extent column refers to; a buffer holds extent * per elements.
struct BufferExtents {
  uint64_t uploaded = 0;        // sized by the data uploaded into it, never by allocate()
  uint64_t pixels = 0;          // width * height
  uint64_t shading_points = 0;  // pixels * (mirror depth + 1)
  uint64_t error_tiles = 0;     // pixels / PM_FILM_ERROR_TILE, rounded up
  uint64_t layer_pixels = 0;    // pixels when the film's extra layers are asked for, else 0
  uint64_t caustic_pixels = 0;  // pixels when the scene has mirrors (the only source of caustics), else 0
  uint64_t control_pixels = 0;  // the bias control's pixels (render/bias_control.h)
  uint64_t hit_slots = 0;       // photons per pass * hit slots per photon
  uint64_t hit_records = 0;     // valid hits whose records the trace has room for (grown as needed)
  uint64_t map_hits = 0;        // valid hits the photon map holds room for (grown as needed)
  uint64_t bounds_tiles = 0;    // hit slots / PM_PHOTON_MAP_BOUNDS_TILE, rounded up
  uint64_t gather_tiles = 0;    // pixel tiles (pixel_order.h) when the gather walks the map by tile, else 0
  uint64_t counters = 1;        // small fixed-size counter arrays
  uint64_t elements = 0;        // radiosity elements
  uint64_t link_batch = 0;      // radiosity elements per link batch
  uint64_t link_scratch = 0;    // radiosity link batch entries: elements per batch * nC * 3
};

BufferGroup buffer_group(BufferSlot slot);
size_t buffer_element_bytes(BufferSlot slot);
// Bytes the buffers of group need for extents (uploaded buffers count zero): the memory estimate.
uint64_t buffer_group_bytes(BufferGroup group, const BufferExtents& extents);

class BufferTable {
 public:
  explicit BufferTable(Device& device) : device_(device) {}

  // Every buffer of group sized for extents; buffers whose size did not change are kept (and
  // keep their contents), empty ones are freed. Uploaded buffers are left alone.
  void allocate(BufferGroup group, const BufferExtents& extents);
  // Frees every buffer of group.
  void release(BufferGroup group);
  // Copies bytes into slot's buffer, reallocating it first when it is too small.
  void upload(BufferSlot slot, const void* data, size_t bytes);
  // Copies the contents of another table's buffer (same device) into slot, sized as it; an empty
  // source frees slot's buffer.
  void copy_from(BufferSlot slot, const DeviceBuffer& source);
  template <typename T>
  void upload(BufferSlot slot, const std::vector<T>& data) {
    upload(slot, data.data(), data.size() * sizeof(T));
  }

  DeviceBuffer& operator[](BufferSlot slot) { return buffers_[static_cast<size_t>(slot)]; }
  const DeviceBuffer& operator[](BufferSlot slot) const { return buffers_[static_cast<size_t>(slot)]; }

  // Binds every buffer of the renderer's groups (scene, frame, methods) into the device's slot
  // table, null where none is allocated: several renderers may share one device.
  void bind_all() const;
  // Device bytes held by the table, all groups or one.
  uint64_t bytes() const;
  uint64_t bytes(BufferGroup group) const;

 private:
  Device& device_;
  std::array<DeviceBuffer, kBufferSlotCount> buffers_;
};

}  // namespace pm
