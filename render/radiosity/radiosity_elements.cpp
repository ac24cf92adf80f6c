// Elements with feature-edge normals, their one-rings and smoothing neighbours, in Morton order
// (radiosity_elements.h).
#include "render/radiosity/radiosity_elements.h"

#include <algorithm>
#include <cmath>
#include <numeric>

#include "kernels/common/compat_host.h"
#include "kernels/common/brdf.h"
#include "render/errors.h"
#include "render/host_threads.h"

namespace pm {

namespace {

struct Dvec {
  double x = 0, y = 0, z = 0;
};
Dvec sub(const Float3& a, const Float3& b) { return {double(a.x) - b.x, double(a.y) - b.y, double(a.z) - b.z}; }
Dvec cross(const Dvec& a, const Dvec& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
double dot(const Dvec& a, const Dvec& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
double length(const Dvec& a) { return std::sqrt(dot(a, a)); }
Dvec scaled(const Dvec& a, double s) { return {a.x * s, a.y * s, a.z * s}; }

double refined_triangle_area(const RefinedMesh& mesh, uint32_t r) {
  const Float3& a = mesh.positions[mesh.indices[3 * r]];
  return 0.5 * length(cross(sub(mesh.positions[mesh.indices[3 * r + 1]], a), sub(mesh.positions[mesh.indices[3 * r + 2]], a)));
}

// 10 bits per axis, interleaved: the position's cell in the bounds, for element order.
uint32_t morton3(const Float3& p, const Dvec& lo, const Dvec& extent) {
  auto cell = [](double t) { return uint32_t(std::min(1023.0, std::max(0.0, t * 1024.0))); };
  auto spread = [](uint32_t v) {
    v = (v * 0x00010001u) & 0xFF0000FFu;
    v = (v * 0x00000101u) & 0x0F00F00Fu;
    v = (v * 0x00000011u) & 0xC30C30C3u;
    v = (v * 0x00000005u) & 0x49249249u;
    return v;
  };
  const uint32_t x = cell(extent.x > 0 ? (p.x - lo.x) / extent.x : 0);
  const uint32_t y = cell(extent.y > 0 ? (p.y - lo.y) / extent.y : 0);
  const uint32_t z = cell(extent.z > 0 ? (p.z - lo.z) / extent.z : 0);
  return (spread(x) << 2) | (spread(y) << 1) | spread(z);
}

// Work per thread below which a chunk is not worth a thread of its own.
constexpr size_t kMinVerticesPerChunk = 16384;
constexpr size_t kMinElementsPerChunk = 16384;

// One element as grouped at its vertex, before Morton ordering.
struct Group {
  Dvec seed;    // normal of the first triangle that formed the group
  Dvec sum;     // angle-weighted normal sum
  uint32_t material;
  bool back;
};

}  // namespace

RadiosityElements build_radiosity_elements(const Scene& scene, const RefinedMesh& mesh, float feature_angle_degrees,
                                           bool two_sided) {
  const size_t tris = mesh.triangle_count(), verts = mesh.positions.size();
  const double cos_feature = std::cos(double(feature_angle_degrees) * M_PI / 180.0);

  // Unit face normals of the scene's triangles (refined triangles lie in them); zero: degenerate.
  std::vector<Dvec> face(scene.triangle_count());
  for (size_t t = 0; t < scene.triangle_count(); ++t) {
    const Float3& a = scene.positions[scene.indices[3 * t]];
    const Dvec n = cross(sub(scene.positions[scene.indices[3 * t + 1]], a), sub(scene.positions[scene.indices[3 * t + 2]], a));
    const double len = length(n);
    face[t] = len > 0 ? scaled(n, 1.0 / len) : Dvec{};
  }
  auto usable = [&](size_t r) {
    const uint32_t* v = &mesh.indices[3 * r];
    return v[0] != v[1] && v[1] != v[2] && v[2] != v[0] && length(face[mesh.source[r]]) > 0;
  };

  // Incident corners per vertex (CSR).
  std::vector<uint32_t> first(verts + 1, 0), corners;
  for (size_t r = 0; r < tris; ++r)
    if (usable(r))
      for (int k = 0; k < 3; ++k) ++first[mesh.indices[3 * r + k] + 1];
  std::partial_sum(first.begin(), first.end(), first.begin());
  corners.resize(first[verts]);
  {
    std::vector<uint32_t> fill(first.begin(), first.end() - 1);
    for (size_t r = 0; r < tris; ++r)
      if (usable(r))
        for (uint32_t k = 0; k < 3; ++k) corners[fill[mesh.indices[3 * r + k]]++] = uint32_t(r) << 2 | k;
  }

  // Greedy grouping per vertex and side: a corner joins the first group of its material whose
  // seed normal is within alpha_f, else it starts a group. Vertices are independent: chunks of
  // them group on threads of their own (render/host_threads.h), each numbering its groups from
  // zero and writing them in the order of the vertices' corner lists (contiguous per chunk, so
  // that threads do not share cache lines); joined in vertex order, the groups are numbered as
  // one loop over all vertices would.
  const int sides = two_sided ? 2 : 1;
  const size_t listed = corners.size();
  std::vector<uint32_t> corner_group(size_t(sides) * listed);  // [side][corner list entry]
  const std::vector<IndexRange> vertex_chunks = split_into_chunks(verts, kMinVerticesPerChunk);
  std::vector<std::vector<Group>> chunk_groups(vertex_chunks.size());
  std::vector<std::vector<uint32_t>> chunk_group_vertex(vertex_chunks.size());
  std::vector<size_t> chunk_vertices_with_elements(vertex_chunks.size(), 0);
  for_each_chunk(vertex_chunks, [&](size_t c, IndexRange range) {
    std::vector<Group>& groups = chunk_groups[c];
    for (size_t v = range.begin; v < range.end; ++v) {
      const size_t base = groups.size();
      for (uint32_t i = first[v]; i < first[v + 1]; ++i) {
        const uint32_t r = corners[i] >> 2, k = corners[i] & 3u;
        const uint32_t* tri = &mesh.indices[3 * r];
        // Corner angle weight (normals weighted by the angle a triangle spans at the vertex).
        const Dvec e1 = sub(mesh.positions[tri[(k + 1) % 3]], mesh.positions[v]);
        const Dvec e2 = sub(mesh.positions[tri[(k + 2) % 3]], mesh.positions[v]);
        const double angle = std::atan2(length(cross(e1, e2)), dot(e1, e2));
        const uint32_t material = scene.triangle_material[mesh.source[r]];
        for (int side = 0; side < sides; ++side) {
          const Dvec n = scaled(face[mesh.source[r]], side ? -1.0 : 1.0);
          size_t g = base;
          while (g < groups.size() &&
                 !(groups[g].material == material && groups[g].back == bool(side) && dot(groups[g].seed, n) >= cos_feature))
            ++g;
          if (g == groups.size()) {
            groups.push_back(Group{n, Dvec{}, material, bool(side)});
            chunk_group_vertex[c].push_back(uint32_t(v));
          }
          Group& group = groups[g];
          group.sum = {group.sum.x + angle * n.x, group.sum.y + angle * n.y, group.sum.z + angle * n.z};
          corner_group[size_t(side) * listed + i] = uint32_t(g);  // the chunk's own number
        }
      }
      if (groups.size() > base) ++chunk_vertices_with_elements[c];
    }
  });
  // The chunks' groups in vertex order, and each corner's group by its global number (each
  // chunk copies and scatters its own, at the offset of the groups before it).
  std::vector<uint32_t> chunk_first_group(vertex_chunks.size() + 1, 0);
  RadiosityElements out;
  for (size_t c = 0; c < vertex_chunks.size(); ++c) {
    chunk_first_group[c + 1] = chunk_first_group[c] + uint32_t(chunk_groups[c].size());
    out.vertices_with_elements += chunk_vertices_with_elements[c];
  }
  std::vector<Group> groups_all(chunk_first_group.back());
  std::vector<uint32_t> group_vertex(chunk_first_group.back());
  std::vector<uint32_t> corner_element(2 * 3 * tris, PM_RADIOSITY_NONE);  // [side][3 r + k]
  for_each_chunk(vertex_chunks, [&](size_t c, IndexRange range) {
    const uint32_t first_group = chunk_first_group[c];
    std::copy(chunk_groups[c].begin(), chunk_groups[c].end(), groups_all.begin() + first_group);
    std::copy(chunk_group_vertex[c].begin(), chunk_group_vertex[c].end(), group_vertex.begin() + first_group);
    for (size_t i = first[range.begin]; i < first[range.end]; ++i)
      for (int side = 0; side < sides; ++side)
        corner_element[size_t(side) * 3 * tris + 3 * (corners[i] >> 2) + (corners[i] & 3u)] =
            corner_group[size_t(side) * listed + i] + first_group;
  });
  const size_t count = groups_all.size();
  if (count >= size_t(PM_RADIOSITY_NONE) / 4)
    throw InputError(scene.source + ": " + std::to_string(count) + " radiosity elements are too many for 32-bit links");

  // Morton order.
  Dvec lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
  for (const Float3& p : mesh.positions) {
    lo = {std::min(lo.x, double(p.x)), std::min(lo.y, double(p.y)), std::min(lo.z, double(p.z))};
    hi = {std::max(hi.x, double(p.x)), std::max(hi.y, double(p.y)), std::max(hi.z, double(p.z))};
  }
  const Dvec extent{hi.x - lo.x, hi.y - lo.y, hi.z - lo.z};
  std::vector<uint32_t> code(count), order(count), rank(count);
  parallel_for(count, kMinElementsPerChunk, [&](size_t begin, size_t end) {
    for (size_t g = begin; g < end; ++g) code[g] = morton3(mesh.positions[group_vertex[g]], lo, extent);
  });
  std::iota(order.begin(), order.end(), 0u);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return code[a] < code[b]; });
  for (size_t i = 0; i < count; ++i) rank[order[i]] = uint32_t(i);
  parallel_for(corner_element.size(), kMinElementsPerChunk, [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i)
      if (corner_element[i] != PM_RADIOSITY_NONE) corner_element[i] = rank[corner_element[i]];
  });

  // Per material, the glossy lobe's albedo for light arriving uniformly from the hemisphere:
  // brdf_glossy_albedo averaged over theta_o with weight 2 mu (midpoint rule, 64 points).
  std::vector<float> glossy_albedo(scene.materials.size(), 0.0f);
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    const MaterialDesc& desc = scene.materials[m];
    if (!(desc.glossy.x > 0 || desc.glossy.y > 0 || desc.glossy.z > 0)) continue;
    double mean = 0;
    for (int i = 0; i < 64; ++i) {
      const float mu = (float(i) + 0.5f) / 64.0f;
      mean += 2.0 * double(mu) * brdf_glossy_albedo(desc.glossy_exponent, mu) / 64.0;
    }
    glossy_albedo[m] = float(mean);
  }

  out.data.resize(2 * count);
  out.vertex.resize(count);
  out.back.resize(count);
  parallel_for(count, kMinElementsPerChunk, [&](size_t begin, size_t end) {
    for (size_t g = begin; g < end; ++g) {
      const Group& group = groups_all[g];
      const size_t e = rank[g];
      const double len = length(group.sum);
      const Dvec n = len > 0 ? scaled(group.sum, 1.0 / len) : group.seed;
      const Float3& p = mesh.positions[group_vertex[g]];
      out.data[2 * e] = float4{p.x, p.y, p.z, PM_AS_FLOAT(group.material)};
      out.data[2 * e + 1] = float4{float(n.x), float(n.y), float(n.z),
                                   group.material < glossy_albedo.size() ? glossy_albedo[group.material] : 0.0f};
      out.vertex[e] = group_vertex[g];
      out.back[e] = group.back;
    }
  });

  out.triangles.resize(2 * tris);
  parallel_for(tris, kMinElementsPerChunk, [&](size_t begin, size_t end) {
    for (size_t r = begin; r < end; ++r) {
      const uint32_t* f = &corner_element[3 * r];
      const uint32_t* b = &corner_element[3 * tris + 3 * r];
      out.triangles[2 * r] = uint4{f[0], f[1], f[2], mesh.source[r]};
      out.triangles[2 * r + 1] = uint4{b[0], b[1], b[2], 0};
    }
  });

  // One-ring entries grouped by element, then the deduplicated smoothing neighbours.
  std::vector<uint32_t> ring_first(count + 1, 0);
  for (size_t s = 0; s < size_t(sides); ++s)
    for (size_t i = 0; i < 3 * tris; ++i)
      if (corner_element[s * 3 * tris + i] != PM_RADIOSITY_NONE) ++ring_first[corner_element[s * 3 * tris + i] + 1];
  std::partial_sum(ring_first.begin(), ring_first.end(), ring_first.begin());
  out.adjacency.resize(ring_first[count]);
  std::vector<uint32_t> fill(ring_first.begin(), ring_first.end() - 1);
  for (size_t s = 0; s < size_t(sides); ++s)
    for (size_t i = 0; i < 3 * tris; ++i) {
      const uint32_t e = corner_element[s * 3 * tris + i];
      if (e != PM_RADIOSITY_NONE) out.adjacency[fill[e]++] = uint32_t(i / 3) << 2 | uint32_t(i % 3);
    }
  out.ranges.assign(count + 1, uint4{0, 0, 0, 0});
  // Smoothing neighbours with their weights. Element e's value stands for its hat function, whose
  // integral is a_e = (one-ring area) / 3, so the film's power is sum_e a_e I_e. A pass
  // I'_e = I_e + sum_j w_ej (I_j - I_e) keeps that sum when a_e w_ej = a_j w_je: w_ej is
  // (3 / 7) (area of the triangles e and j share) / (e's one-ring area). On a regular mesh
  // (six equal triangles around each vertex) that is eq. 5's 1 / 7 per neighbour; on any mesh the
  // weights of an element's neighbours add up to 6 / 7. Eq. 5's plain mean over the corners
  // does not keep the power where elements differ in size or valence (docs/accuracy.md).
  // Elements are independent: chunks of them on threads of their own, joined in element order.
  const std::vector<IndexRange> element_chunks = split_into_chunks(count, kMinElementsPerChunk);
  std::vector<std::vector<uint32_t>> chunk_neighbours(element_chunks.size());
  std::vector<std::vector<float>> chunk_weights(element_chunks.size());
  for_each_chunk(element_chunks, [&](size_t c, IndexRange range) {
    std::vector<std::pair<uint32_t, double>> shared;  // (neighbour, triangle area it shares)
    std::vector<uint32_t>& neighbours = chunk_neighbours[c];
    std::vector<float>& weights = chunk_weights[c];
    for (size_t e = range.begin; e < range.end; ++e) {
      out.ranges[e].x = ring_first[e];
      out.ranges[e].y = uint32_t(neighbours.size());  // within the chunk until joined
      const size_t side_base = out.back[e] ? 3 * tris : 0;
      shared.clear();
      double ring_area = 0;
      for (uint32_t i = ring_first[e]; i < ring_first[e + 1]; ++i) {
        const uint32_t r = out.adjacency[i] >> 2, k = out.adjacency[i] & 3u;
        const double area = refined_triangle_area(mesh, r);
        ring_area += area;
        for (uint32_t step = 1; step < 3; ++step) {
          const uint32_t other = corner_element[side_base + 3 * r + (k + step) % 3];
          if (other != PM_RADIOSITY_NONE && other != e) shared.emplace_back(other, area);
        }
      }
      std::sort(shared.begin(), shared.end());
      for (size_t i = 0; i < shared.size(); ++i) {
        if (i > 0 && shared[i].first == shared[i - 1].first) {
          weights.back() += float(3.0 / 7.0 * shared[i].second / ring_area);
          continue;
        }
        neighbours.push_back(shared[i].first);
        weights.push_back(ring_area > 0 ? float(3.0 / 7.0 * shared[i].second / ring_area) : 0.0f);
      }
    }
  });
  // Joined in element order: each chunk copies its own at the offset of the chunks before it.
  std::vector<size_t> chunk_first_neighbour(element_chunks.size() + 1, 0);
  for (size_t c = 0; c < element_chunks.size(); ++c)
    chunk_first_neighbour[c + 1] = chunk_first_neighbour[c] + chunk_neighbours[c].size();
  const size_t neighbour_count = chunk_first_neighbour.back();
  out.adjacency.resize(ring_first[count] + neighbour_count);
  out.smooth_weights.resize(neighbour_count);
  for_each_chunk(element_chunks, [&](size_t c, IndexRange range) {
    const size_t offset = chunk_first_neighbour[c];
    for (size_t e = range.begin; e < range.end; ++e) out.ranges[e].y += uint32_t(ring_first[count] + offset);
    std::copy(chunk_neighbours[c].begin(), chunk_neighbours[c].end(), out.adjacency.begin() + ring_first[count] + offset);
    std::copy(chunk_weights[c].begin(), chunk_weights[c].end(), out.smooth_weights.begin() + offset);
  });
  out.ranges[count].x = ring_first[count];
  out.ranges[count].y = uint32_t(ring_first[count] + neighbour_count);
  return out;
}

}  // namespace pm
