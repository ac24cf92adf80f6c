// Host loops on several threads (render/host_threads.h): chunks cover the loop once, in order;
// a failure on any thread reaches the caller (the lowest chunk's); and what is built from chunks
// joined in order does not depend on how many threads there were (the radiosity elements and
// their texture tints, the host work of radiosity's first frame).
#include <gtest/gtest.h>

#include <cstring>
#include <stdexcept>
#include <thread>

#include "render/host_threads.h"
#include "render/radiosity/mesh_refinement.h"
#include "render/radiosity/radiosity_elements.h"
#include "render/radiosity/radiosity_texture_tint.h"
#include "render/scene_textures.h"

namespace pm {
namespace {

// Restores every hardware thread when a test ends.
struct ThreadLimit {
  explicit ThreadLimit(unsigned threads) { set_host_thread_limit(threads); }
  ~ThreadLimit() { set_host_thread_limit(0); }
};

TEST(HostThreads, ChunksCoverTheLoopOnceInOrder) {
  for (size_t count : {0, 1, 7, 1000, 123457}) {
    for (size_t min_chunk : {1, 64, 100000}) {
      const std::vector<IndexRange> chunks = split_into_chunks(count, min_chunk);
      ASSERT_FALSE(chunks.empty());
      EXPECT_LE(chunks.size(), host_thread_count());
      EXPECT_EQ(chunks.front().begin, 0u);
      EXPECT_EQ(chunks.back().end, count);
      for (size_t c = 1; c < chunks.size(); ++c) {
        EXPECT_EQ(chunks[c].begin, chunks[c - 1].end);
        EXPECT_GE(chunks[c - 1].end - chunks[c - 1].begin, min_chunk) << count << " in chunks of " << min_chunk;
      }
    }
  }
  ThreadLimit one(1);
  EXPECT_EQ(split_into_chunks(1000000, 1).size(), 1u);
}

TEST(HostThreads, TheLowestChunksFailureReachesTheCaller) {
  const std::vector<IndexRange> chunks{{0, 1}, {1, 2}, {2, 3}};
  try {
    for_each_chunk(chunks, [](size_t c, IndexRange) {
      if (c > 0) throw std::runtime_error("chunk " + std::to_string(c));
    });
    FAIL() << "no failure came back";
  } catch (const std::runtime_error& e) {
    EXPECT_STREQ(e.what(), "chunk 1");
  }
}

// A textured plane of many small triangles: more vertices and triangles than one chunk takes.
Scene fine_textured_plane() {
  Scene s;
  s.positions = {{0, 0, 0}, {8, 0, 0}, {8, 0, 8}, {0, 0, 8}};
  s.indices = {0, 3, 2, 0, 2, 1};
  s.triangle_material = {0, 0};
  s.triangle_uvs = {{0, 0}, {0, 1}, {1, 1}, {0, 0}, {1, 1}, {1, 0}};
  TextureImage image;
  image.source = "test";
  image.width = image.height = 4;
  image.file_channels = 4;
  for (int i = 0; i < 16; ++i) image.rgba.insert(image.rgba.end(), {uint8_t(16 * i), uint8_t(255 - 9 * i), 128, 255});
  s.images = {image};
  s.textures = {TextureRef{0, TextureWrap::repeat, TextureWrap::repeat}};
  MaterialDesc textured;
  textured.base_color_texture = 0;
  s.materials = {textured};
  return s;
}

TEST(HostThreads, RadiosityElementsAndTintsDoNotDependOnTheThreads) {
  if (std::thread::hardware_concurrency() < 2) GTEST_SKIP() << "one hardware thread: every loop runs as one chunk";
  const Scene scene = fine_textured_plane();
  const RefinedMesh mesh = refine_mesh(scene, 0.03);  // about 140,000 triangles, 70,000 vertices
  ASSERT_GT(mesh.positions.size(), 4 * size_t(16384));
  DeviceTextures textures;
  pack_texture_images(scene, &textures);
  auto build = [&](unsigned threads, std::vector<float4>* tints) {
    ThreadLimit limit(threads);
    RadiosityElements elements = build_radiosity_elements(scene, mesh, 40.0f, true);
    *tints = radiosity_texture_tints(scene, mesh, elements, textures);
    return elements;
  };
  std::vector<float4> tints_one, tints_many;
  const RadiosityElements one = build(1, &tints_one), many = build(0, &tints_many);
  ASSERT_EQ(one.count(), many.count());
  auto same_bits = [](const auto& a, const auto& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(a[0])) == 0;
  };
  EXPECT_TRUE(same_bits(one.data, many.data));
  EXPECT_TRUE(same_bits(one.ranges, many.ranges));
  EXPECT_TRUE(same_bits(one.adjacency, many.adjacency));
  EXPECT_TRUE(same_bits(one.smooth_weights, many.smooth_weights));
  EXPECT_TRUE(same_bits(one.triangles, many.triangles));
  EXPECT_TRUE(same_bits(one.vertex, many.vertex));
  EXPECT_EQ(one.vertices_with_elements, many.vertices_with_elements);
  EXPECT_TRUE(same_bits(tints_one, tints_many));
  EXPECT_NE(tints_one.front().x, tints_one.back().x) << "the texture varies over the plane";
}

}  // namespace
}  // namespace pm
