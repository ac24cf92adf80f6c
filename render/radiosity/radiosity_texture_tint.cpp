// Hat-weighted texture means per radiosity element (radiosity_texture_tint.h), accumulated
// triangle by triangle into the triangles' corner elements (the lookups on several threads).
#include "render/radiosity/radiosity_texture_tint.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "kernels/common/compat_host.h"
#include "kernels/common/texture.h"
#include "render/host_threads.h"

namespace pm {

namespace {

constexpr int kSubdivision = 4;  // 4 x 4 = 16 sample points per refined triangle

struct Rgb {
  double r = 0, g = 0, b = 0;
};

// The sample points: barycentrics (b1, b2) of the centroids of the kSubdivision^2 equal
// sub-triangles (pointing up: i + j < n; pointing down: i + j < n - 1).
std::vector<std::array<double, 2>> sample_points() {
  std::vector<std::array<double, 2>> points;
  const double n = kSubdivision;
  for (int i = 0; i < kSubdivision; ++i)
    for (int j = 0; i + j < kSubdivision; ++j) {
      points.push_back({(i + 1.0 / 3.0) / n, (j + 1.0 / 3.0) / n});
      if (i + j < kSubdivision - 1) points.push_back({(i + 2.0 / 3.0) / n, (j + 2.0 / 3.0) / n});
    }
  return points;
}

double area(const Float3& a, const Float3& b, const Float3& c) {
  const double e1[3] = {double(b.x) - a.x, double(b.y) - a.y, double(b.z) - a.z};
  const double e2[3] = {double(c.x) - a.x, double(c.y) - a.y, double(c.z) - a.z};
  const double n[3] = {e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]};
  return 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
}

Vec3 vec(const Float3& p) { return vec3(p.x, p.y, p.z); }

// Corner sums of one refined triangle: per corner, the hat-weighted texel sum and its weight.
struct CornerSums {
  Rgb sum[3];
  double weight[3] = {0, 0, 0};
};

// Refined triangles per block of texture lookups, and per thread of a block.
constexpr size_t kTrianglesPerBlock = size_t(1) << 16;
constexpr size_t kMinTrianglesPerChunk = 2048;

// The hat-weighted texture sums of refined triangle r's three corners (area times hat weight
// times texel), or false where its material has no base-colour texture.
bool corner_texture_sums(const Scene& scene, const RefinedMesh& mesh, const DeviceTextures& textures,
                         const std::vector<std::array<double, 2>>& points, size_t r, CornerSums* out) {
  const uint32_t source = mesh.source[r];
  if (scene.triangle_material[source] >= scene.materials.size()) return false;
  const MaterialDesc& material = scene.materials[scene.triangle_material[source]];
  if (material.base_color_texture < 0) return false;
  const Float3 o[3] = {scene.positions[scene.indices[3 * source]], scene.positions[scene.indices[3 * source + 1]],
                       scene.positions[scene.indices[3 * source + 2]]};
  Float2 uv_o[3] = {};
  if (3 * size_t(source) + 2 < scene.triangle_uvs.size())
    for (int k = 0; k < 3; ++k) uv_o[k] = scene.triangle_uvs[3 * size_t(source) + k];
  // The refined corners' texture coordinates, from their place in the scene triangle.
  Float3 p[3];
  double uv[3][2];
  for (int k = 0; k < 3; ++k) {
    p[k] = mesh.positions[mesh.indices[3 * r + k]];
    float b1, b2;
    triangle_barycentrics(vec(p[k]), vec(o[0]), vec(o[1]), vec(o[2]), &b1, &b2);
    const double b0 = 1.0 - b1 - b2;
    uv[k][0] = b0 * uv_o[0].u + b1 * uv_o[1].u + b2 * uv_o[2].u;
    uv[k][1] = b0 * uv_o[0].v + b1 * uv_o[1].v + b2 * uv_o[2].v;
  }
  const double a = area(p[0], p[1], p[2]);
  *out = CornerSums{};
  for (const auto& s : points) {
    const double b[3] = {1.0 - s[0] - s[1], s[0], s[1]};
    const float u = float(b[0] * uv[0][0] + b[1] * uv[1][0] + b[2] * uv[2][0]);
    const float v = float(b[0] * uv[0][1] + b[1] * uv[1][1] + b[2] * uv[2][1]);
    const float4 t = texture_sample(textures.info.data(), textures.texels.data(), textures.srgb_table.data(),
                                    uint32_t(material.base_color_texture), u, v, 1);
    for (int k = 0; k < 3; ++k) {
      out->sum[k].r += a * b[k] * t.x;
      out->sum[k].g += a * b[k] * t.y;
      out->sum[k].b += a * b[k] * t.z;
      out->weight[k] += a * b[k];
    }
  }
  return true;
}

}  // namespace

std::vector<float4> radiosity_texture_tints(const Scene& scene, const RefinedMesh& mesh,
                                            const RadiosityElements& elements, const DeviceTextures& textures) {
  const size_t count = elements.count();
  std::vector<float4> tints(count, float4{1, 1, 1, 0});
  const std::vector<std::array<double, 2>> points = sample_points();

  // Each refined triangle of a textured material adds, for each corner, its area times the
  // hat-weighted texture sum to the corner's element on either side (rad_triangles' corners,
  // the same triangles as the elements' one-rings). The texture lookups, most of the work, run
  // a block of triangles at a time on threads of their own (render/host_threads.h); the sums are
  // added in triangle order, so the tints are the same however many threads there are.
  std::vector<Rgb> sum(count);
  std::vector<double> weight(count, 0.0);
  std::vector<CornerSums> block(std::min(mesh.triangle_count(), kTrianglesPerBlock));
  std::vector<uint8_t> textured(block.size());
  for (size_t first = 0; first < mesh.triangle_count(); first += block.size()) {
    const size_t n = std::min(block.size(), mesh.triangle_count() - first);
    parallel_for(n, kMinTrianglesPerChunk, [&](size_t begin, size_t end) {
      for (size_t i = begin; i < end; ++i)
        textured[i] = corner_texture_sums(scene, mesh, textures, points, first + i, &block[i]) ? 1 : 0;
    });
    for (size_t i = 0; i < n; ++i) {
      if (!textured[i]) continue;
      const size_t r = first + i;
      for (size_t side = 0; side < 2; ++side) {
        const uint4 corners = elements.triangles[2 * r + side];
        const uint32_t element[3] = {corners.x, corners.y, corners.z};
        for (int k = 0; k < 3; ++k) {
          if (element[k] == PM_RADIOSITY_NONE) continue;
          sum[element[k]].r += block[i].sum[k].r;
          sum[element[k]].g += block[i].sum[k].g;
          sum[element[k]].b += block[i].sum[k].b;
          weight[element[k]] += block[i].weight[k];
        }
      }
    }
  }
  for (size_t e = 0; e < count; ++e)
    if (weight[e] > 0)
      tints[e] = float4{float(sum[e].r / weight[e]), float(sum[e].g / weight[e]), float(sum[e].b / weight[e]), 0};
  return tints;
}

}  // namespace pm
