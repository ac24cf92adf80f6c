// Host tests of the radiosity stage functions (kernels/common/radiosity_*.h), called directly on
// host data: link directions cosine-weighted, link merging and compact storage keeping the
// weights' sum (the hemisphere integral), gathering in the units of eq. 3 and 4, smoothing that
// never crosses a feature edge (eq. 5, 6), and light links (eq. 2) against an independent
// quadrature.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "kernels/common/compat_host.h"
#include "kernels/common/radiosity_gather.h"
#include "kernels/common/radiosity_light.h"
#include "kernels/common/radiosity_links.h"
#include "render/radiosity/radiosity_elements.h"
#include "render/renderer.h"
#include "render/scene_bvh.h"
#include "support/radiosity_host_mesh.h"
#include "support/radiosity_meshes.h"

namespace pm {
namespace {

using test::HostMesh;

// Link origins over the one-ring (PM_RADIOSITY_ORIGINS_ONE_RING): every origin lies in a triangle
// of the element's one-ring, with that triangle's normal on the element's side, and their mean is
// the hat-weighted centroid of the one-ring, sum A_t (2 v + b + c) / 12 over sum A_t / 3 (the
// integral of x phi_v over each triangle): the density is proportional to the hat function.
TEST(RadiosityLinkOrigins, OneRingPointsDistributedByTheHatFunction) {
  Scene flat = test::folded_sheet(1.0f, 1.0f, 0.0f);  // a flat 1 x 2 m sheet, normal +y
  HostMesh h(flat, 0.3, 40.0f, true);
  h.p.link_origins = PM_RADIOSITY_ORIGINS_ONE_RING;
  size_t checked = 0;
  for (uint32_t e = 0; e < h.el.count(); ++e) {
    const Vec3 v = vec3_from_float4(h.el.data[2 * e]), n = vec3_from_float4(h.el.data[2 * e + 1]);
    Vec3 weighted = vec3_splat(0.0f);
    double mass = 0, reach = 0;
    for (uint32_t r = h.el.ranges[e].x; r < h.el.ranges[e + 1].x; ++r) {
      Vec3 b, c, face_n;
      const float twice_area = radiosity_ring_triangle(&h.kg, e, h.el.adjacency[r], &b, &c, &face_n);
      weighted = vec3_add(weighted, vec3_scale(vec3_add(vec3_add(vec3_scale(v, 2.0f), b), c), twice_area / 24.0f));
      mass += twice_area / 6.0;
      reach = std::max({reach, double(vec3_length(vec3_sub(b, v))), double(vec3_length(vec3_sub(c, v)))});
    }
    const uint32_t draws = 4096;
    Vec3 mean = vec3_splat(0.0f);
    for (uint32_t k = 0; k < draws; ++k) {
      Vec3 normal;
      const Vec3 x = radiosity_link_origin(&h.kg, &h.p, e, k, &normal);
      ASSERT_NEAR(x.y, 0.0f, 1e-6f) << "on the sheet";
      ASSERT_LE(vec3_length(vec3_sub(x, v)), reach * (1 + 1e-5)) << "within the one-ring";
      ASSERT_GT(vec3_dot(normal, n), 0.999f) << "the face normal on the element's side";
      mean = vec3_add(mean, vec3_scale(x, 1.0f / draws));
    }
    const Vec3 expected = vec3_scale(weighted, float(1.0 / mass));
    // 4096 draws over a one-ring of 0.3 m triangles: the mean's noise is about 0.1 / 64 m.
    EXPECT_NEAR(mean.x, expected.x, 0.006) << "element " << e;
    EXPECT_NEAR(mean.z, expected.z, 0.006) << "element " << e;
    ++checked;
  }
  EXPECT_GT(checked, 20u);
}

// The glossy lobe's directional albedo (brdf_glossy_albedo, which radiosity uses for glossy
// materials) against brdf_eval integrated over the hemisphere on a fine grid in (cos theta, phi).
TEST(RadiosityGlossyAlbedo, MatchesTheLobeIntegratedOverTheHemisphere) {
  Material m{};
  m.glossy = float4{1, 1, 1, 0};
  for (float exponent : {1.28f, 8.0f, 64.0f}) {
    m.glossy.w = exponent;
    double previous = 2;
    for (float mu : {1.0f, 0.8f, 0.5f, 0.2f}) {
      const Vec3 n = vec3(0, 0, 1), wo = vec3(std::sqrt(1 - mu * mu), 0, mu);
      const int steps = 1024;
      double integral = 0;
      for (int i = 0; i < steps; ++i)
        for (int j = 0; j < steps; ++j) {
          const double cos_t = (i + 0.5) / steps, phi = 2 * M_PI * (j + 0.5) / steps;
          const double sin_t = std::sqrt(1 - cos_t * cos_t);
          const Vec3 wi = vec3(float(sin_t * std::cos(phi)), float(sin_t * std::sin(phi)), float(cos_t));
          integral += brdf_eval(&m, n, wi, wo).x * cos_t * (2 * M_PI / (double(steps) * steps));
        }
      const double albedo = brdf_glossy_albedo(exponent, mu);
      EXPECT_NEAR(albedo, integral, 0.01 * integral + 1e-3) << "n " << exponent << " mu " << mu;
      EXPECT_LE(albedo, previous + 1e-6) << "falls towards grazing";
      if (mu == 1.0f) {
        EXPECT_NEAR(albedo, 1.0, 0.01);
      }
      previous = albedo;
    }
  }
}

TEST(RadiosityDirections, CosineWeightedOverTheHemisphere) {
  for (uint32_t n : {16u, 256u, 1000u}) {
    double mean[3] = {0, 0, 0};
    uint32_t inner = 0;
    for (uint32_t k = 0; k < n; ++k) {
      Vec3 d = radiosity_direction(k, n, 0.3f);
      ASSERT_NEAR(vec3_length(d), 1.0f, 1e-5f);
      ASSERT_GT(d.z, 0.0f);
      mean[0] += d.x / n;
      mean[1] += d.y / n;
      mean[2] += d.z / n;
      inner += d.z * d.z > 0.5f;  // cos^2 > 1/2: half of a cosine-weighted set (sin^2 theta uniform)
    }
    // E[cos theta] = 2/3 for the cosine-weighted density cos theta / pi; no sideways bias.
    EXPECT_NEAR(mean[2], 2.0 / 3.0, 1.0 / n);
    EXPECT_NEAR(mean[0], 0.0, 4.0 / n);
    EXPECT_NEAR(mean[1], 0.0, 4.0 / n);
    EXPECT_NEAR(double(inner) / n, 0.5, 1.0 / n);
  }
  // In world space, around any normal.
  std::mt19937 rng(3);
  std::normal_distribution<float> g;
  for (int i = 0; i < 20; ++i) {
    Vec3 normal = vec3_normalize(vec3(g(rng), g(rng), g(rng)));
    double mean_cos = 0;
    for (uint32_t k = 0; k < 256; ++k) {
      const float c = vec3_dot(radiosity_world_direction(normal, uint32_t(i), k, 256), normal);
      ASSERT_GT(c, 0.0f);
      mean_cos += c / 256.0;
    }
    EXPECT_NEAR(mean_cos, 2.0 / 3.0, 1e-3);
  }
}

TEST(RadiosityLinks, MergeAndStoreKeepEveryWeightAndTheirSum) {
  const uint32_t nc = 8, batch = 3, per = 3 * nc;
  std::vector<uint32_t> links(2 * batch * per), counts(4 * batch), words(512);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> pick(0, 5);
  std::uniform_real_distribution<float> w(0.0f, 1.0f / float(per));
  // Targets close together (one word each) and far apart (escaped: two words).
  const uint32_t ids[6] = {9, 3, 12, 3000000, 3000001, PM_RADIOSITY_NONE};
  std::vector<std::map<uint32_t, double>> expected(batch);
  std::vector<double> sums(batch, 0.0);
  for (uint32_t e = 0; e < batch; ++e)
    for (uint32_t j = 0; j < per; ++j) {
      const uint32_t t = ids[pick(rng)];
      const float weight = t == PM_RADIOSITY_NONE ? 0.0f : w(rng);
      links[2 * (e * per + j)] = t;
      links[2 * (e * per + j) + 1] = PM_AS_UINT(weight);
      if (t != PM_RADIOSITY_NONE) {
        expected[e][t] += weight;
        sums[e] += weight;
      }
    }
  KernelGlobals kg{};
  kg.rad_batch_links = links.data();
  kg.rad_batch_counts = counts.data();
  kg.rad_links = words.data();
  LaunchParams p{};
  p.link_directions = nc;
  for (uint32_t e = 0; e < batch; ++e) kernel_radiosity_link_merge(&kg, &p, e);
  uint32_t offset = 0;  // the host's offsets: the running sum of the words
  for (uint32_t e = 0; e < batch; ++e) {
    counts[4 * e + 2] = offset;
    offset += counts[4 * e];
  }
  for (uint32_t e = 0; e < batch; ++e) kernel_radiosity_link_store(&kg, &p, e);
  for (uint32_t e = 0; e < batch; ++e) {
    ASSERT_EQ(counts[4 * e + 3], expected[e].size());
    // Escapes: the first far target after a near one, and the first link if its target is far.
    uint32_t expected_words = 0, previous = 0;
    for (const auto& [target, weight] : expected[e]) {
      expected_words += target - previous >= 0xffffu ? 2 : 1;
      previous = target;
    }
    EXPECT_EQ(counts[4 * e], expected_words);
    uint32_t quantised_sum = 0, at = counts[4 * e + 2], target = 0;
    for (const auto& [expected_target, weight] : expected[e]) {  // ascending, one link per target
      float decoded = 0;
      target = radiosity_next_link(words.data(), &at, target, &decoded);
      EXPECT_EQ(target, expected_target);
      EXPECT_NEAR(decoded, weight, 1.0 / 65535.0);
      quantised_sum += uint32_t(std::lround(decoded * 65535.0));
    }
    EXPECT_EQ(at, counts[4 * e + 2] + counts[4 * e]);  // every word read, no more
    // The quantised weights sum to the rounded sum: nothing lost or gained in compression.
    EXPECT_NEAR(double(quantised_sum), sums[e] * 65535.0, 1.0);
  }
}

TEST(RadiosityGather, OneBounceInTheUnitsOfEquationsThreeAndFour) {
  // Two elements seeing only each other: element 0's links put all of its hemisphere on
  // element 1 (weight 1), and element 1's half of it on element 0.
  std::vector<Material> materials(1);
  materials[0].diffuse = float4{0.5f, 0.25f, 1.0f, 0};
  std::vector<float4> elements = {{0, 0, 0, PM_AS_FLOAT(0)}, {0, 0, 1, 0}, {0, 0, 1, PM_AS_FLOAT(0)}, {0, 0, -1, 0}};
  std::vector<uint4> ranges = {{0, 0, 0, 0}, {0, 0, 1, 0}, {0, 0, 2, 0}};
  std::vector<uint32_t> links = {1u << 16 | 65535u, 0u << 16 | 32768u};  // (delta << 16) | unorm16 weight
  std::vector<float4> radiance = {{0, 0, 0, 0}, {2, 2, 2, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  std::vector<float4> irradiance(4, float4{0, 0, 0, 0});
  KernelGlobals kg{};
  kg.materials = materials.data();
  kg.rad_elements = elements.data();
  kg.rad_element_ranges = ranges.data();
  kg.rad_links = links.data();
  kg.rad_radiance = radiance.data();
  kg.rad_irradiance = irradiance.data();
  LaunchParams p{};
  p.element_count = 2;
  p.radiosity_source = 0;
  for (uint32_t e = 0; e < 2; ++e) kernel_radiosity_gather(&kg, &p, e);
  // E = pi * w * L: element 0 gathers pi * 1 * 2; it reflects rho / pi * E.
  EXPECT_NEAR(irradiance[0].x, 2.0 * M_PI, 1e-5);
  EXPECT_NEAR(radiance[2].x, 0.5 * 2.0, 1e-5);
  EXPECT_NEAR(radiance[2].y, 0.25 * 2.0, 1e-5);
  EXPECT_NEAR(irradiance[1].x, 0.0, 1e-6);  // element 0 had no outgoing radiance yet
  // Second bounce (from the other half): element 1 gathers half its hemisphere of element 0.
  p.radiosity_source = 1;
  for (uint32_t e = 0; e < 2; ++e) kernel_radiosity_gather(&kg, &p, e);
  EXPECT_NEAR(irradiance[1].x, M_PI * (32768.0 / 65535.0) * 1.0, 1e-4);
  EXPECT_NEAR(irradiance[0].x, 2.0 * M_PI, 1e-5);  // I_total keeps bounce 1 (eq. 3)
}

TEST(RadiositySmooth, NeverCrossesAFeatureEdge) {
  for (float fold : {90.0f, 10.0f}) {
    HostMesh h(test::folded_sheet(1.0f, 1.0f, fold), 0.25, 40.0f, true);
    const size_t n = h.el.count();
    // Light on the front of the floor only (normal +y), none elsewhere.
    auto floor_front = [&](size_t e) { return !h.el.back[e] && h.el.normal(e).y > 0.999f; };
    for (size_t e = 0; e < n; ++e) h.irradiance[e] = floor_front(e) ? float4{1, 1, 1, 0} : float4{0, 0, 0, 0};
    h.p.radiosity_source = 0;
    for (uint32_t e = 0; e < n; ++e) kernel_radiosity_smooth(&h.kg, &h.p, e);
    size_t mixed = 0;
    for (size_t e = 0; e < n; ++e) {
      const float v = h.irradiance[n + e].x;
      if (fold == 90.0f) {
        EXPECT_EQ(v, floor_front(e) ? 1.0f : 0.0f) << "element " << e;
      }
      mixed += v > 0.0f && v < 1.0f;
    }
    // A 10 degree fold is no feature edge: the light is averaged across it.
    if (fold == 10.0f) {
      EXPECT_GT(mixed, 0u);
    } else {
      EXPECT_EQ(mixed, 0u);
    }
  }
  // Eq. 6 holds in the kernel itself: a neighbour beyond alpha_f is skipped even if listed.
  std::vector<float4> elements = {{0, 0, 0, 0}, {0, 1, 0, 0}, {1, 0, 0, 0}, {1, 0, 0, 0}};
  std::vector<uint4> ranges = {{0, 0, 0, 0}, {0, 1, 0, 0}, {0, 2, 0, 0}};
  std::vector<uint32_t> adjacency = {1, 0};
  std::vector<float> weights = {0.5f, 0.5f};
  std::vector<float4> irradiance = {{1, 1, 1, 0}, {5, 5, 5, 0}, {0, 0, 0, 0}, {0, 0, 0, 0}};
  KernelGlobals kg{};
  kg.rad_elements = elements.data();
  kg.rad_element_ranges = ranges.data();
  kg.rad_adjacency = adjacency.data();
  kg.rad_smooth_weights = weights.data();
  kg.rad_irradiance = irradiance.data();
  LaunchParams p{};
  p.element_count = 2;
  p.feature_cos = std::cos(40.0f * float(M_PI) / 180.0f);
  kernel_radiosity_smooth(&kg, &p, 0);
  EXPECT_EQ(irradiance[2].x, 1.0f);
  p.feature_cos = std::cos(100.0f * float(M_PI) / 180.0f);  // alpha_f 100 degrees: 90 is within
  kernel_radiosity_smooth(&kg, &p, 0);
  EXPECT_EQ(irradiance[2].x, 3.0f);
}

// The corners of refined triangle r.
void refined_corners(const HostMesh& h, uint32_t r, Vec3 c[3]) {
  for (int j = 0; j < 3; ++j) {
    const Float3& q = h.mesh.positions[h.mesh.indices[3 * r + j]];
    c[j] = vec3(q.x, q.y, q.z);
  }
}

// The film's power of the smoothed irradiance, sum_e a_e I_e with a_e a third of e's one-ring
// area, is what it was before the pass, on either side of a feature edge and on refined
// triangles of every size; a uniform irradiance stays uniform.
TEST(RadiositySmooth, KeepsThePowerOfTheInterpolatedIrradiance) {
  for (float fold : {90.0f, 10.0f}) {
    HostMesh h(test::folded_sheet(1.0f, 0.37f, fold), 0.11, 40.0f, true);
    const size_t n = h.el.count();
    std::vector<double> hat_area(n, 0.0);
    for (size_t e = 0; e < n; ++e)
      for (uint32_t i = h.el.ranges[e].x; i < h.el.ranges[e + 1].x; ++i) {
        Vec3 c[3];
        refined_corners(h, h.el.adjacency[i] >> 2, c);
        hat_area[e] += vec3_length(vec3_cross(vec3_sub(c[1], c[0]), vec3_sub(c[2], c[0]))) / 6.0;
      }
    auto power = [&](size_t half) {
      double sum = 0;
      for (size_t e = 0; e < n; ++e) sum += hat_area[e] * h.irradiance[half * n + e].x;
      return sum;
    };
    // A field that varies over the mesh: a peak near one corner of the floor.
    for (size_t e = 0; e < n; ++e) {
      const Float3 q = h.el.position(e);
      const float v = 1.0f / (0.05f + q.x * q.x + q.z * q.z);
      h.irradiance[e] = float4{v, v, v, 0};
    }
    h.p.radiosity_source = 0;
    for (uint32_t e = 0; e < n; ++e) kernel_radiosity_smooth(&h.kg, &h.p, e);
    EXPECT_NEAR(power(1), power(0), 1e-5 * power(0)) << "fold " << fold;
    size_t changed = 0;
    for (size_t e = 0; e < n; ++e) changed += h.irradiance[n + e].x != h.irradiance[e].x;
    EXPECT_GT(changed, n / 2) << "the pass smoothed";
    for (size_t e = 0; e < n; ++e) h.irradiance[e] = float4{2, 2, 2, 0};
    for (uint32_t e = 0; e < n; ++e) kernel_radiosity_smooth(&h.kg, &h.p, e);
    for (size_t e = 0; e < n; ++e) EXPECT_NEAR(h.irradiance[n + e].x, 2.0f, 1e-5f) << "element " << e;
  }
}

// Phi / (4 pi r^2) cos theta of an unoccluded point light at x with normal n.
double point_irradiance(const Float3& light, double power, const Vec3& x, const Vec3& n) {
  const double dx = light.x - x.x, dy = light.y - x.y, dz = light.z - x.z;
  const double r2 = dx * dx + dy * dy + dz * dz;
  const double c = (dx * n.x + dy * n.y + dz * n.z) / std::sqrt(r2);
  return c > 0 ? power * c / (4 * M_PI * r2) : 0.0;
}

// Element e's one-ring: the mean irradiance over it (integrated on a grid of steps^2 equal
// sub-triangles per triangle, at their centroids) and its area.
double ring_mean_irradiance(const HostMesh& h, size_t e, const Float3& light, double power, double* ring_area = nullptr) {
  const Vec3 normal = vec3_from_float4(h.el.data[2 * e + 1]);
  double integral = 0, area_sum = 0;
  for (uint32_t i = h.el.ranges[e].x; i < h.el.ranges[e + 1].x; ++i) {
    Vec3 c[3];
    refined_corners(h, h.el.adjacency[i] >> 2, c);
    const double area = 0.5 * vec3_length(vec3_cross(vec3_sub(c[1], c[0]), vec3_sub(c[2], c[0])));
    const int steps = 64;
    double sum = 0;
    for (int a = 0; a < steps; ++a)
      for (int b = 0; a + b < steps; ++b)
        for (double offset : {1.0 / 3, 2.0 / 3}) {
          if (offset > 0.5 && a + b > steps - 2) continue;
          const double wa = (a + offset) / steps, wb = (b + offset) / steps;
          const Vec3 x = vec3_add(vec3_add(vec3_scale(c[0], float(1 - wa - wb)), vec3_scale(c[1], float(wa))),
                                  vec3_scale(c[2], float(wb)));
          sum += point_irradiance(light, power, x, normal);
        }
    integral += area * sum / (steps * steps);
    area_sum += area;
  }
  if (ring_area) *ring_area = area_sum;
  return integral / area_sum;
}

// Unshadowed: the vertex mode gives the vertex's own irradiance (eq. 2 times Phi / 4 pi); the
// one-ring mode the mean irradiance over the one-ring, exactly, however close the light (2 cm
// above the sheet here, where the vertex value is far off), so the power the interpolated
// irradiance carries is the power reaching the sheet. The element's bounce-0 radiance is rho / pi
// times it; back sides, facing away, get nothing.
TEST(RadiosityLightLinks, VertexValueAndExactOneRingMean) {
  for (float height : {0.6f, 0.02f}) {
    Scene flat = test::folded_sheet(1.0f, 1.0f, 0.0f);  // a flat 1 x 2 m sheet, normal +y
    flat.lights[0].position = {0.4f, height, 0.3f};
    const Float3 light = flat.lights[0].position;
    const double rho = flat.materials[0].diffuse.x, power = flat.lights[0].power.x;
    HostMesh h(flat, 0.3, 40.0f, true);
    double worst_vertex_vs_mean = 0;
    for (int mode : {PM_RADIOSITY_LIGHT_VERTEX, PM_RADIOSITY_LIGHT_ONE_RING}) {
      h.p.light_sampling = uint32_t(mode);
      for (uint32_t e = 0; e < h.el.count(); ++e) kernel_radiosity_light_links(&h.kg, &h.p, e);
      double carried = 0, reaching = 0;
      for (size_t e = 0; e < h.el.count(); ++e) {
        EXPECT_EQ(h.irradiance[e].x, 0.0f);  // I_total reset for the gathering
        if (h.el.back[e]) {
          EXPECT_EQ(h.radiance[e].x, 0.0f);
          continue;
        }
        double ring_area = 0;
        const double mean = ring_mean_irradiance(h, e, light, power, &ring_area);
        const double at_vertex = point_irradiance(light, power, vec3_from_float4(h.el.data[2 * e]), vec3(0, 1, 0));
        const double expected = rho / M_PI * (mode == PM_RADIOSITY_LIGHT_VERTEX ? at_vertex : mean);
        EXPECT_NEAR(h.radiance[e].x, expected, 2e-3 * expected) << "element " << e << " mode " << mode;
        carried += h.radiance[e].x / (rho / M_PI) * ring_area / 3;
        reaching += mean * ring_area / 3;
        worst_vertex_vs_mean = std::max(worst_vertex_vs_mean, std::fabs(at_vertex / mean - 1));
      }
      if (mode == PM_RADIOSITY_LIGHT_ONE_RING) {
        EXPECT_NEAR(carried, reaching, 2e-3 * reaching);
      }
    }
    // Why the vertex mode is not the default: near the light, vertex values miss the power.
    std::printf("light %.2f m above: vertex values differ from the one-ring means by up to %.0f %%\n", height,
                100 * worst_vertex_vs_mean);
    if (height < 0.1f) {
      EXPECT_GT(worst_vertex_vs_mean, 0.5);
    }
  }
}

// A shadow edge between vertices: the vertex sample sees all or nothing, the one-ring's
// oversampled visibility gives the elements near the edge a partial value.
TEST(RadiosityLightLinks, OneRingOversamplesShadowEdgesBetweenVertices) {
  Scene scene = test::folded_sheet(1.0f, 1.0f, 0.0f);
  scene.lights[0].position = {0.5f, 1.0f, 0.5f};
  const Float3 light = scene.lights[0].position;
  const double rho = scene.materials[0].diffuse.x, power = scene.lights[0].power.x;
  // A blocker half way up: a square at y = 0.5 covering x < 0.55, whose shadow edge on the sheet
  // (x = 0.6) falls between the vertices at 0.5 and 0.625.
  const uint32_t b = uint32_t(scene.positions.size());
  scene.positions.insert(scene.positions.end(), {{-1, 0.5f, -2}, {0.55f, 0.5f, -2}, {0.55f, 0.5f, 2}, {-1, 0.5f, 2}});
  scene.indices.insert(scene.indices.end(), {b, b + 1, b + 2, b, b + 2, b + 3});
  scene.triangle_material.insert(scene.triangle_material.end(), {0, 0});
  HostMesh h(scene, 0.15, 40.0f, false);
  size_t partial = 0, checked = 0;
  for (int mode : {PM_RADIOSITY_LIGHT_VERTEX, PM_RADIOSITY_LIGHT_ONE_RING}) {
    h.p.light_sampling = uint32_t(mode);
    for (uint32_t e = 0; e < h.el.count(); ++e) kernel_radiosity_light_links(&h.kg, &h.p, e);
    for (size_t e = 0; e < h.el.count(); ++e) {
      const Float3 p = h.el.position(e);
      if (p.y != 0.0f) continue;  // the sheet's elements only
      const double v = h.radiance[e].x / (rho / M_PI);
      if (mode == PM_RADIOSITY_LIGHT_VERTEX) {
        const double lit = point_irradiance(light, power, vec3(p.x, p.y, p.z), vec3(0, 1, 0));
        EXPECT_NEAR(v, p.x < 0.6f ? 0.0 : lit, 1e-5 * lit) << "element " << e;
        ++checked;
      } else {
        const double lit = ring_mean_irradiance(h, e, light, power);
        // More than one 0.125 m ring away from the edge: all or nothing.
        if (p.x < 0.45f || p.x > 0.75f) {
          EXPECT_NEAR(v, p.x < 0.45f ? 0.0 : lit, 2e-3 * lit) << "element " << e;
        }
        EXPECT_LE(v, lit * (1 + 2e-3));
        partial += v > 0.05 * lit && v < 0.95 * lit;
      }
    }
  }
  EXPECT_GT(checked, 20u);
  EXPECT_GE(partial, 2u);
}

}  // namespace
}  // namespace pm
