// Checks of a Device that every backend must pass, written once and run by the OpenCL test
// binary (PoCL in CI) and the GPU test binary (CUDA on the GPU machine).
#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>
#include <functional>
#include <memory>
#include <numeric>
#include <random>
#include <stdexcept>
#include <vector>

#include "render/device.h"
#include "render/errors.h"

namespace pm::test {

// The backend's first device, or nullptr when the machine has none (the caller skips).
inline std::unique_ptr<Device> open_first_device(const std::string& backend) {
  for (const DeviceInfo& info : list_devices())
    if (info.backend == backend) return create_device(backend, info.index);
  return nullptr;
}

// One OpenCL device shared by all tests of a binary that ask for it (building the program is the
// slow part on PoCL); throws when the machine has none.
inline Device& shared_opencl_device() {
  static std::unique_ptr<Device> d = open_first_device("opencl");
  if (!d) throw std::runtime_error("no OpenCL device");
  return *d;
}

// An OpenCL device on the same GPU as CUDA (NVIDIA's OpenCL driver) when there is one, else the
// first OpenCL device: for comparing the backends on one GPU.
inline std::unique_ptr<Device> open_opencl_preferring_gpu() {
  for (const DeviceInfo& info : list_devices())
    if (info.backend == "opencl" && info.platform.find("NVIDIA") != std::string::npos)
      return create_device("opencl", info.index);
  return open_first_device("opencl");
}

// The device compiler sees the shared structs exactly as the host does, and by-value launch
// parameters arrive intact.
inline void check_layout_agrees(Device& device) {
  DeviceBuffer probe = device.allocate(16 * sizeof(uint32_t), "layout probe");
  device.bind(BufferSlot::layout_probe, probe);
  LaunchParams params{};
  params.width = 0x12345678u;
  params.sort_tile_count = 0x9abcdef0u;
  params.camera.up.w = 1234.5f;
  params.ray_epsilon = -0.25f;
  device.launch(KernelId::layout_probe, 1, params);
  uint32_t out[16] = {};
  device.download(probe, out, sizeof(out));
  device.unbind(BufferSlot::layout_probe);
  LaunchParams host;
  EXPECT_EQ(out[0], sizeof(Material));
  EXPECT_EQ(out[1], sizeof(PointLight));
  EXPECT_EQ(out[2], sizeof(CameraParams));
  EXPECT_EQ(out[3], sizeof(LaunchParams));
  EXPECT_EQ(out[4], uint32_t(reinterpret_cast<char*>(&host.width) - reinterpret_cast<char*>(&host)));
  EXPECT_EQ(out[5], uint32_t(reinterpret_cast<char*>(&host.mirror_depth) - reinterpret_cast<char*>(&host)));
  EXPECT_EQ(out[6], uint32_t(reinterpret_cast<char*>(&host.ray_epsilon) - reinterpret_cast<char*>(&host)));
  EXPECT_EQ(out[7], uint32_t(reinterpret_cast<char*>(&host.sort_tile_count) - reinterpret_cast<char*>(&host)));
  EXPECT_EQ(out[8], 0x12345678u);
  EXPECT_EQ(out[9], 0x9abcdef0u);
  float up_w, eps;
  std::memcpy(&up_w, &out[10], 4);
  std::memcpy(&eps, &out[11], 4);
  EXPECT_EQ(up_w, 1234.5f);
  EXPECT_EQ(eps, -0.25f);
}

// Sorts (keys, values) by the low key_bits into the output pair: Device::sort_pairs, or another
// sort on the same buffers (the portable sort on a backend that has a library sort).
using SortPairs = std::function<void(DeviceBuffer& keys_in, DeviceBuffer& values_in, DeviceBuffer& keys_out,
                                     DeviceBuffer& values_out, uint32_t count, int key_bits)>;

// sort_pairs is a stable sort by the low key_bits into the output buffers, for sizes around the
// tile boundaries.
inline void check_sort_pairs(Device& device, uint32_t count, int key_bits, uint32_t seed, const SortPairs& sort = {}) {
  std::mt19937 rng(seed);
  std::vector<uint32_t> keys(count), values(count);
  const uint32_t mask = key_bits >= 32 ? 0xffffffffu : ((1u << key_bits) - 1);
  // Few distinct keys, so stability is exercised.
  for (uint32_t i = 0; i < count; ++i) keys[i] = (rng() % 997u * 2654435761u) & mask;
  std::iota(values.begin(), values.end(), 0u);

  size_t bytes = size_t(count) * sizeof(uint32_t);
  DeviceBuffer keys_in = device.allocate(bytes, "keys in"), values_in = device.allocate(bytes, "values in");
  DeviceBuffer keys_out = device.allocate(bytes, "keys out"), values_out = device.allocate(bytes, "values out");
  device.upload(keys_in, keys.data(), bytes);
  device.upload(values_in, values.data(), bytes);
  if (sort)
    sort(keys_in, values_in, keys_out, values_out, count, key_bits);
  else
    device.sort_pairs(keys_in, values_in, keys_out, values_out, count, key_bits);
  std::vector<uint32_t> sorted_keys(count), sorted_values(count);
  device.download(keys_out, sorted_keys.data(), bytes);
  device.download(values_out, sorted_values.data(), bytes);

  std::vector<uint32_t> order(count);
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return keys[a] < keys[b]; });
  for (uint32_t i = 0; i < count; ++i) {
    ASSERT_EQ(sorted_values[i], order[i]) << "at " << i << " of " << count;
    ASSERT_EQ(sorted_keys[i], keys[order[i]]) << "at " << i << " of " << count;
  }
}

}  // namespace pm::test
