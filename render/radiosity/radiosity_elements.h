// The elements of vertex link radiosity and their neighbourhoods, built on the host from the
// refined mesh: a vertex becomes one element per group of incident triangles that share a
// material, a side (front = the winding's normal; back as well for two-sided surfaces) and a
// normal within the feature angle alpha_f, so normals respect feature edges (a cube corner has
// three elements per side) and radiance never has to be continuous across them. Each element
// keeps its one-ring (the incident triangles of its group, for the light links' oversampling)
// and its smoothing neighbours (the other corners of those triangles, eq. 5). Elements are put
// in Morton order of their positions so that link rays and gathering read memory coherently.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "render/radiosity/mesh_refinement.h"

namespace pm {

struct RadiosityElements {
  std::vector<float4> data;        // 2 per element: (position, material index bits), (unit normal, 0)
  // elements + 1 rows: (first one-ring entry, first smoothing neighbour, first link, 0); row
  // e + 1 ends element e's ranges. Links are filled in by the link build.
  std::vector<uint4> ranges;
  std::vector<uint32_t> adjacency;  // one-ring entries (refined triangle << 2 | corner), then neighbours
  // One per smoothing neighbour, in the neighbours' order (entry j of adjacency has weight
  // j - ranges[count()].x): the share of the neighbour's value that one smoothing pass moves to
  // the element (radiosity_gather.h, kernel_radiosity_smooth).
  std::vector<float> smooth_weights;
  std::vector<uint4> triangles;     // 2 per refined triangle: front corner elements (w: source
                                    // triangle), back corner elements (w: 0); PM_RADIOSITY_NONE: none
  std::vector<uint32_t> vertex;     // refined-mesh vertex of each element
  std::vector<uint8_t> back;        // 1 for an element of a back side
  size_t vertices_with_elements = 0;

  size_t count() const { return vertex.size(); }
  // Element e's normal and position as the host sees them.
  Float3 normal(size_t e) const { return Float3{data[2 * e + 1].x, data[2 * e + 1].y, data[2 * e + 1].z}; }
  Float3 position(size_t e) const { return Float3{data[2 * e].x, data[2 * e].y, data[2 * e].z}; }
};

// Throws InputError when the elements would not fit 32-bit indices.
RadiosityElements build_radiosity_elements(const Scene& scene, const RefinedMesh& mesh, float feature_angle_degrees,
                                           bool two_sided);

}  // namespace pm
