// Hidden link origins (kernels/common/radiosity_links.h, radiosity_light.h), on the host: a thin
// closed slab sunk into a floor under a glowing ceiling. The floor vertices whose one-rings reach
// under the slab must gather what the floor beside the slab gathers, and receive the light it
// receives, when the rays and quadrature points inside the slab are left out; counted in, they
// darken those vertices by the hidden share of their one-ring. Also: the merge scales the seen
// rays' weights so that they keep the sum of a fully seen element, and reports the hidden count;
// and a closed room, wound either way, has no hidden origins.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <utility>
#include <vector>

#include "kernels/common/compat_host.h"
#include "kernels/common/radiosity_gather.h"
#include "kernels/common/radiosity_light.h"
#include "kernels/common/radiosity_links.h"
#include "support/radiosity_host_mesh.h"
#include "support/radiosity_meshes.h"
#include "support/room_scenes.h"

namespace pm {
namespace {

using test::HostMesh;

constexpr uint32_t kDirections = 256;
constexpr double kMaxEdge = 0.1;

// The slab's turn about the vertical: its edges cross the floor's refined mesh at every offset,
// so the light links' quadrature (four points per one-ring triangle) meets them without a pattern.
constexpr float kSlabTurn = 0.4f;

// (x, z) turned by -kSlabTurn: a floor point in the slab's own frame.
Vec3 in_slab_frame(Vec3 x) {
  const float c = std::cos(kSlabTurn), s = std::sin(kSlabTurn);
  return vec3(c * x.x + s * x.z, x.y, -s * x.x + c * x.z);
}

// A 2 x 2 m floor (y = 0, facing up) under a ceiling 1 m above (facing down), and, when `slab`, a
// closed 0.3 x 0.01 x 0.3 m slab (outward winding) half sunk into the floor's middle, turned by
// kSlabTurn. A point light under the ceiling.
Scene floor_under_ceiling(bool slab) {
  Scene s;
  s.name = "slab";
  s.source = "test";
  s.materials = {test::grey_material(0.5f)};
  test::add_quad(s, {-1, 0, -1}, {-1, 0, 1}, {1, 0, 1}, {1, 0, -1});  // normal +y
  test::add_quad(s, {-1, 1, -1}, {1, 1, -1}, {1, 1, 1}, {-1, 1, 1});  // normal -y
  if (slab) {
    const size_t first = s.positions.size();
    test::add_box(s, {-0.15f, -0.005f, -0.15f}, {0.15f, 0.005f, 0.15f});
    const float c = std::cos(kSlabTurn), sn = std::sin(kSlabTurn);
    for (size_t i = first; i < s.positions.size(); ++i) {
      const Float3 p = s.positions[i];
      s.positions[i] = {c * p.x - sn * p.z, p.y, sn * p.x + c * p.z};
    }
  }
  s.lights = {LightDesc{"light", {0.3f, 0.9f, 0.2f}, {10, 10, 10}}};
  return s;
}

// The link build of every element in one batch, as VertexLinkRadiosity::build_links runs it
// (trace, merge, the host's offsets and hidden counts, store); returns the hidden counts.
std::vector<uint32_t> build_links(HostMesh& h, std::vector<uint32_t>& batch, std::vector<uint32_t>& counts,
                                  std::vector<uint32_t>& words) {
  const uint32_t elements = uint32_t(h.el.count());
  batch.assign(size_t(elements) * kDirections * 3 * 2, 0);
  counts.assign(4 * size_t(elements), 0);
  h.kg.rad_batch_links = batch.data();
  h.kg.rad_batch_counts = counts.data();
  h.p.link_directions = kDirections;
  h.p.link_origins = PM_RADIOSITY_ORIGINS_ONE_RING;
  h.p.batch_first = 0;
  h.p.batch_count = elements;
  for (uint32_t i = 0; i < elements * kDirections; ++i) kernel_radiosity_link_trace(&h.kg, &h.p, i);
  for (uint32_t e = 0; e < elements; ++e) kernel_radiosity_link_merge(&h.kg, &h.p, e);
  std::vector<uint32_t> hidden(elements);
  uint32_t total = 0;
  for (uint32_t e = 0; e < elements; ++e) {
    hidden[e] = counts[4 * e + 2];
    h.el.ranges[e].w = hidden[e];
    counts[4 * e + 2] = total;
    h.el.ranges[e].z = total;
    total += counts[4 * e];
  }
  h.el.ranges[elements].z = total;
  words.assign(total + 1, 0);
  h.kg.rad_links = words.data();
  for (uint32_t e = 0; e < elements; ++e) kernel_radiosity_link_store(&h.kg, &h.p, e);
  return hidden;
}

struct FloorValues {
  std::vector<Vec3> positions;
  std::vector<double> gathered, direct;  // E / pi from a ceiling of radiance 1; direct irradiance
  std::vector<uint32_t> hidden;
};

// The front-side floor elements' gathered irradiance (one bounce from a ceiling of outgoing
// radiance 1) and direct irradiance from the light, with origins nearer than `hidden_edges` max
// edges to a back face left out.
FloorValues floor_values(bool slab, float hidden_edges) {
  HostMesh h(floor_under_ceiling(slab), kMaxEdge, 40.0f, true);
  h.p.link_hidden_distance = hidden_edges * float(kMaxEdge);
  std::vector<uint32_t> batch, counts, words;
  const std::vector<uint32_t> hidden = build_links(h, batch, counts, words);
  FloorValues out;
  for (uint32_t e = 0; e < h.el.count(); ++e) {
    const Vec3 x = vec3_from_float4(h.el.data[2 * e]), n = vec3_from_float4(h.el.data[2 * e + 1]);
    h.radiance[e] = x.y > 0.99f && n.y < -0.99f ? float4{1, 1, 1, 0} : float4{0, 0, 0, 0};  // the ceiling's lower side
  }
  h.p.radiosity_source = 0;
  for (uint32_t e = 0; e < h.el.count(); ++e) kernel_radiosity_gather(&h.kg, &h.p, e);
  const std::vector<float4> gathered = h.irradiance;
  h.p.light_sampling = PM_RADIOSITY_LIGHT_ONE_RING;
  for (uint32_t e = 0; e < h.el.count(); ++e) kernel_radiosity_light_links(&h.kg, &h.p, e);
  const double rho = 0.5;
  for (uint32_t e = 0; e < h.el.count(); ++e) {
    const Vec3 x = vec3_from_float4(h.el.data[2 * e]), n = vec3_from_float4(h.el.data[2 * e + 1]);
    if (!(std::fabs(x.y) < 1e-6f && n.y > 0.99f)) continue;  // the floor's upper side only
    out.positions.push_back(x);
    out.gathered.push_back(gathered[e].x / M_PI);
    out.direct.push_back(h.radiance[e].x / (rho / M_PI));
    out.hidden.push_back(hidden[e]);
  }
  return out;
}

// Floor vertices outside the slab but near enough for their one-rings to reach under it (the
// refined floor's edges are 6.25 cm long, 8.8 cm on the diagonal).
bool at_the_slab_edge(Vec3 x) {
  const Vec3 local = in_slab_frame(x);
  const float d = std::fmax(std::fabs(local.x), std::fabs(local.z));
  return d > 0.15f && d < 0.21f;
}

TEST(RadiosityHiddenOrigins, VerticesBesideASunkSlabGatherWhatTheOpenFloorGathers) {
  const FloorValues open = floor_values(false, 1.0f), kept = floor_values(true, 1.0f), counted = floor_values(true, 0.0f);
  ASSERT_EQ(open.positions.size(), kept.positions.size());  // the slab does not change the floor's mesh
  double sum_open = 0, sum_kept = 0, sum_counted = 0, direct_open = 0, direct_kept = 0, direct_counted = 0;
  size_t edge = 0, some_hidden = 0;
  for (size_t i = 0; i < open.positions.size(); ++i) {
    EXPECT_EQ(open.hidden[i], 0u) << "nothing is hidden on an open floor";
    if (!at_the_slab_edge(open.positions[i])) continue;
    ++edge;
    some_hidden += kept.hidden[i] > 0;
    sum_open += open.gathered[i];
    sum_kept += kept.gathered[i];
    sum_counted += counted.gathered[i];
    direct_open += open.direct[i];
    direct_kept += kept.direct[i];
    direct_counted += counted.direct[i];
  }
  std::printf("%zu floor vertices at the slab's edge (%zu with hidden origins): gathered %.4f open, %.4f kept, "
              "%.4f counted; direct %.4f open, %.4f kept, %.4f counted\n",
              edge, some_hidden, sum_open / edge, sum_kept / edge, sum_counted / edge, direct_open / edge,
              direct_kept / edge, direct_counted / edge);
  ASSERT_GE(edge, 16u);
  EXPECT_GT(some_hidden, edge / 2);
  // Measured: gathered -1.0 % and direct -2.1 % with the hidden origins left out (the slab's sides
  // stand 5 mm above the floor, and the light links' four-point quadrature meets its edges
  // coarsely), -13 and -14 % with them counted in.
  EXPECT_NEAR(sum_kept / sum_open, 1.0, 0.03);
  EXPECT_NEAR(direct_kept / direct_open, 1.0, 0.03);
  EXPECT_LT(sum_counted / sum_open, 0.92);
  EXPECT_LT(direct_counted / direct_open, 0.92);
}

// A room wound outwards is seen from inside through the back sides of its faces: its corners
// put walls' backs within a max edge of every origin near them, and none of those is hidden (an
// origin on a back side never is). Wound inwards, the same room has none either.
TEST(RadiosityHiddenOrigins, NoneInARoomWhateverItsWinding) {
  for (bool outwards : {true, false}) {
    Scene room;
    room.name = "room";
    room.source = "test";
    room.materials = {test::grey_material(0.5f)};
    test::add_box(room, {0, 0, 0}, {1, 1, 1});
    if (!outwards)
      for (size_t t = 0; 3 * t < room.indices.size(); ++t) std::swap(room.indices[3 * t + 1], room.indices[3 * t + 2]);
    room.lights = {LightDesc{"light", {0.5f, 0.9f, 0.5f}, {10, 10, 10}}};
    HostMesh h(room, kMaxEdge, 40.0f, true);
    h.p.link_hidden_distance = float(kMaxEdge);
    std::vector<uint32_t> batch, counts, words;
    const std::vector<uint32_t> hidden = build_links(h, batch, counts, words);
    uint32_t total = 0;
    for (uint32_t n : hidden) total += n;
    EXPECT_EQ(total, 0u) << (outwards ? "wound outwards" : "wound inwards");
  }
}

}  // namespace
}  // namespace pm
