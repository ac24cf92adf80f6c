// Numerical extremes (docs: ../shared/design/testing.md section 5), end to end on the OpenCL
// backend and, where a kernel function decides the outcome, on the host: scene scales from 1e-3
// to 1e5, grazing light, a light on a surface, lights whose photons never make a recorded hit,
// tiny and huge r_max and smoothing, a single photon, degenerate triangles, photon counts near
// 2^32, and photons emitted at the poles. Every render must give finite layers with no repaired
// pixel and bounded energy; what cannot be rendered must be refused with a message naming the
// option (the film's own guard against non-finite sums: renderer_film_test.cpp).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include "kernels/common/compat_host.h"
#include "kernels/common/footprint.h"
#include "kernels/common/photon_differentials.h"
#include "render/errors.h"
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "support/render_settings.h"
#include "support/analytic_scenes.h"
#include "support/device_checks.h"
#include "support/paths.h"
#include "support/room_scenes.h"
#include "support/still_render.h"

namespace pm {
namespace {

Device& device() { return test::shared_opencl_device(); }

using Rendered = test::StillRender;
using test::layer_mean;

Rendered render(const Scene& scene, const RenderSettings& settings, int width = 40, int height = 40) {
  return test::render_still(device(), scene, settings, width, height);
}

RenderSettings photons(uint64_t per_pass, uint32_t passes = 1) {
  PhotonSettings p;
  p.photons = per_pass;
  return test::photon_render_settings(p, passes);
}

double scene_area(const Scene& s) { return test::surface_area(s); }

double mean_power(const Scene& s) {
  double p = 0;
  for (const LightDesc& l : s.lights) p += (l.power.x + l.power.y + l.power.z) / 3.0;
  return p;
}

// A loose upper bound for the mean indirect radiance: light that is reflected with albedo rho
// spreads Phi rho / (1 - rho) over every bounce; spread uniformly over the scene's area A it gives
// radiance rho / pi * that / A. The bound allows 20 times that, which catches blow-ups (a factor
// of 1/area gone wrong, an overflowing density) and not small biases.
double indirect_bound(const Scene& s, double rho) {
  return 20.0 * rho / M_PI * mean_power(s) * rho / (1.0 - rho) / scene_area(s);
}

// Every layer finite, nothing repaired by the film stage.
void expect_clean(const Rendered& r, const std::string& what) {
  EXPECT_EQ(r.stats.repaired_pixels, 0) << what;
  for (const ImageLayer& layer : r.image.layers) {
    size_t bad = 0;
    for (float v : layer.rgb) bad += !std::isfinite(v) || v < 0.0f;
    EXPECT_EQ(bad, 0u) << what << ": layer '" << layer.name << "' has non-finite or negative values";
  }
}

Scene floor_scene(Float3 light, float albedo) {
  Scene s;
  s.name = "floor";
  MaterialDesc m;
  m.diffuse = {albedo, albedo, albedo};
  s.materials = {m};
  test::add_quad(s, {-5, 0, -5}, {-5, 0, 5}, {5, 0, 5}, {5, 0, -5});
  s.lights = {LightDesc{"l", light, {10, 10, 10}}};
  s.camera.position = {0, 3, -3};
  s.camera.look_at = {0, 0, 0};
  return s;
}

// --- scene scale -------------------------------------------------------------------------------

TEST(Extremes, SceneScaleFromMillimetresTo100Kilometres) {
  // The Cornell box with its light lowered to mid-height: right under the ceiling, the ceiling's
  // 1/r^2 hot spot would dominate the image mean and the comparison.
  Scene base = builtin_cornell_box();
  base.lights[0].position.y = 0.4f;
  const RenderSettings settings = photons(16384);
  const Rendered reference = render(base, settings);
  expect_clean(reference, "scale 1");
  const double direct1 = layer_mean(reference.image, "direct"), indirect1 = layer_mean(reference.image, "indirect");
  const double s1 = reference.stats.method.get("smoothing");
  ASSERT_GT(direct1, 0.0);
  ASSERT_GT(indirect1, 0.0);
  for (double k : {1e-3, 1e-2, 1e2, 1e3, 1e5}) {
    const Scene s = test::scaled(base, k);
    const Rendered r = render(s, settings);
    const std::string what = "scale " + std::to_string(k);
    expect_clean(r, what);
    const double direct = layer_mean(r.image, "direct"), indirect = layer_mean(r.image, "indirect");
    const double smoothing = r.stats.method.get("smoothing");
    std::printf("scale %-8g direct %.5f (x%.4f)  indirect %.5f (x%.4f)  s %.4g (x k^(3/4) %.4f)  hits %llu\n", k,
                direct, direct / direct1, indirect, indirect / indirect1, smoothing, smoothing / s1 / std::pow(k, 0.75),
                (unsigned long long)r.stats.method.get("hits"));
    // Same irradiance at every scale: ray offsets follow the scene's size (kernels/common/ray.h),
    // and the automatic smoothing grows as k^(3/4), so that footprints grow as k
    // (render/footprint_scale.h): the same image.
    EXPECT_NEAR(direct / direct1, 1.0, 0.005) << what;
    EXPECT_NEAR(indirect / indirect1, 1.0, 0.01) << what;
    EXPECT_NEAR(smoothing / s1 / std::pow(k, 0.75), 1.0, 0.001) << what;
    EXPECT_LT(indirect, indirect_bound(s, 0.74)) << what;
  }
  // A fixed s is the paper's rule, |a| = s Delta L^(1/4) (kernels/common/footprint.h): not scale
  // invariant. At 1e5 the footprints of s = 8 reach no shading point; s x k^(3/4) restores them.
  const double k = 1e5;
  RenderSettings fixed = settings;
  test::edit_photons(fixed).smoothing = 8;
  EXPECT_EQ(layer_mean(render(test::scaled(base, k), fixed).image, "indirect"), 0.0);
  test::edit_photons(fixed).smoothing = float(8 * std::pow(k, 0.75));
  const Rendered r = render(test::scaled(base, k), fixed);
  expect_clean(r, "scale 1e5, s x k^(3/4)");
  EXPECT_NEAR(layer_mean(r.image, "indirect") / indirect1, 1.0, 0.1);
}

// --- light placement -----------------------------------------------------------------------------

TEST(Extremes, GrazingLightJustAboveAFloor) {
  for (float height : {1e-2f, 1e-4f, 1e-6f}) {
    Scene s = floor_scene({0, height, 0}, 0.7f);
    test::add_quad(s, {-5, 0, 5}, {-5, 5, 5}, {5, 5, 5}, {5, 0, 5});  // a back wall for second bounces
    s.triangle_material.back() = s.triangle_material.front();
    const Rendered r = render(s, photons(20000));
    expect_clean(r, "light at height " + std::to_string(height));
    EXPECT_LT(layer_mean(r.image, "indirect"), indirect_bound(s, 0.7)) << height;
  }
}

TEST(Extremes, LightOnTheSurfaceOfAWall) {
  Scene s = builtin_cornell_box();
  const Float3 on_floor{0.278f, 0.0f, 0.2796f}, on_ceiling{0.278f, 0.5488f, 0.2796f}, on_wall{0.0f, 0.27f, 0.28f};
  for (Float3 position : {on_floor, on_ceiling, on_wall}) {
    s.lights[0].position = position;  // on the floor, on the ceiling, on the green wall
    const Rendered r = render(s, photons(16384));
    expect_clean(r, "light on a wall");
    EXPECT_GT(layer_mean(r.image, "direct"), 0.0);
    EXPECT_LT(layer_mean(r.image, "indirect"), indirect_bound(s, 0.74));
  }
}

TEST(Extremes, NoRecordedHitsGivesAnEmptyPhotonMap) {
  // Open floor: every photon's first hit is direct light (not recorded) and its reflection
  // escapes. Light below the floor: half the photons hit its underside, the rest escape.
  for (Float3 light : {Float3{0, 1, 0}, Float3{0, -1, 0}}) {
    const Scene s = floor_scene(light, 0.7f);
    const Rendered r = render(s, photons(10000));
    expect_clean(r, "open floor");
    EXPECT_EQ(r.stats.method.get("hits"), 0.0);
    EXPECT_EQ(layer_mean(r.image, "indirect"), 0.0);
    EXPECT_EQ(layer_mean(r.image, "caustic"), 0.0);
  }
  // A light enclosed in a black box: every photon is absorbed at its first hit.
  Scene enclosed = builtin_cornell_box();
  MaterialDesc black;
  black.diffuse = {0, 0, 0};
  enclosed.materials.push_back(black);
  const uint32_t m = uint32_t(enclosed.materials.size() - 1);
  const Float3 c = enclosed.lights[0].position;
  const float e = 0.02f;
  auto p = [&](float x, float y, float z) { return Float3{c.x + x * e, c.y + y * e, c.z + z * e}; };
  test::add_quad(enclosed, p(-1, -1, -1), p(1, -1, -1), p(1, -1, 1), p(-1, -1, 1), m);
  test::add_quad(enclosed, p(-1, 1, -1), p(-1, 1, 1), p(1, 1, 1), p(1, 1, -1), m);
  test::add_quad(enclosed, p(-1, -1, -1), p(-1, 1, -1), p(1, 1, -1), p(1, -1, -1), m);
  test::add_quad(enclosed, p(-1, -1, 1), p(1, -1, 1), p(1, 1, 1), p(-1, 1, 1), m);
  test::add_quad(enclosed, p(-1, -1, -1), p(-1, -1, 1), p(-1, 1, 1), p(-1, 1, -1), m);
  test::add_quad(enclosed, p(1, -1, -1), p(1, 1, -1), p(1, 1, 1), p(1, -1, 1), m);
  const Rendered r = render(enclosed, photons(10000));
  expect_clean(r, "enclosed light");
  EXPECT_EQ(r.stats.method.get("hits"), 0.0);
  EXPECT_EQ(layer_mean(r.image, ""), 0.0);
}

TEST(Extremes, NearlyCoincidentHitsInsideTinyBoxes) {
  // A closed white box around the light, 1 mm and 10 micrometres wide: every recorded hit lies
  // inside it, so the photon map's bounds (and Morton codes) span the box. Ray offsets follow the
  // scene's size (kernels/common/ray.h), so the photons stay inside even the 10-micrometre box;
  // the camera outside sees nothing, neither through the walls nor, from footprints reaching past
  // the box's edges, beside them (kernels/common/footprint_clip.h, gather_reach.h).
  for (float e : {5e-4f, 5e-6f}) {
    Scene s;
    s.name = "tiny box";
    MaterialDesc white;
    white.diffuse = {0.8f, 0.8f, 0.8f};
    s.materials = {white};
    test::add_box(s, {-e, -e, -e}, {e, e, e});
    s.lights = {LightDesc{"l", {0, 0, 0}, {1, 1, 1}}};
    s.camera.position = {2 * e, 4 * e, -10 * e};
    s.camera.look_at = {0, 0, 0};
    const Rendered r = render(s, photons(20000));
    const std::string what = "box of " + std::to_string(2 * e) + " m";
    expect_clean(r, what);
    EXPECT_GT(r.stats.method.get("hits"), 10000.0) << what;
    EXPECT_EQ(layer_mean(r.image, ""), 0.0) << what << ": light leaks out";
  }
}

// --- footprint settings ------------------------------------------------------------------------

TEST(Extremes, TinyAndHugeFootprintSettings) {
  const Scene s = builtin_cornell_box();
  const double bound = indirect_bound(s, 0.74);
  struct Case {
    float rmax, smoothing;
  };
  for (Case c : {Case{1e-9f, 8}, Case{1e-30f, 8}, Case{1e6f, 8}, Case{0, 1e-6f}, Case{0, 1e4f}, Case{1e6f, 1e4f},
                 Case{1e-9f, 1e-6f}}) {
    RenderSettings settings = photons(4096);
    test::edit_photons(settings).rmax = c.rmax;
    test::edit_photons(settings).smoothing = c.smoothing;
    const Rendered r = render(s, settings, 24, 24);
    const std::string what = "rmax " + std::to_string(c.rmax) + " smoothing " + std::to_string(c.smoothing);
    expect_clean(r, what);
    const double indirect = layer_mean(r.image, "indirect");
    std::printf("%s: indirect mean %.5g (bound %.3g)\n", what.c_str(), indirect, bound);
    EXPECT_LT(indirect, bound) << what;
  }
}

TEST(Extremes, ZeroNegativeOrNonFiniteFootprintSettingsAreRefused) {
  const Scene s = builtin_cornell_box();
  auto message = [&](float rmax, float smoothing) -> std::string {
    RenderSettings settings = photons(100);
    test::edit_photons(settings).rmax = rmax;
    test::edit_photons(settings).smoothing = smoothing;
    try {
      Renderer renderer(device(), s, settings);
    } catch (const SettingError& e) {
      return e.setting();
    }
    return "(accepted)";
  };
  EXPECT_EQ(message(-1, 8), "rmax");
  EXPECT_EQ(message(INFINITY, 8), "rmax");
  EXPECT_EQ(message(0, -1), "smoothing");
  EXPECT_EQ(message(0, INFINITY), "smoothing");
  EXPECT_EQ(message(0, NAN), "smoothing");
}

TEST(Extremes, OnePhoton) {
  for (uint32_t seed : {1u, 2u, 3u}) {
    RenderSettings settings = photons(1);
    settings.seed = seed;
    const Rendered r = render(builtin_cornell_box(), settings);
    expect_clean(r, "one photon");
    EXPECT_LE(r.stats.method.get("hits"), 4.0);  // at most bounces + 2 records
  }
}

// --- degenerate geometry and watertightness -------------------------------------------------

// A 1 m room open at the front, seen from its axis: the quads' diagonals project exactly onto
// pixel centres, so eye rays run along the edges shared by two triangles.
TEST(Extremes, RaysAlongSharedEdgesHitATriangle) {
  Scene s;
  s.name = "room";
  s.materials = {MaterialDesc{}};
  test::add_quad(s, {0, 0, 0}, {0, 0, 1}, {1, 0, 1}, {1, 0, 0});
  test::add_quad(s, {0, 1, 0}, {1, 1, 0}, {1, 1, 1}, {0, 1, 1});
  test::add_quad(s, {0, 0, 1}, {0, 1, 1}, {1, 1, 1}, {1, 0, 1});
  test::add_quad(s, {0, 0, 0}, {0, 1, 0}, {0, 1, 1}, {0, 0, 1});
  test::add_quad(s, {1, 0, 0}, {1, 0, 1}, {1, 1, 1}, {1, 1, 0});
  s.lights = {LightDesc{"l", {0.5f, 0.9f, 0.5f}, {10, 10, 10}}};
  s.camera.position = {0.5f, 0.5f, -1.35f};
  s.camera.look_at = {0.5f, 0.5f, 0.5f};
  s.camera.vertical_fov_degrees = 40;
  RenderSettings settings = photons(0);
  settings.width = settings.height = 128;
  Renderer renderer(device(), s, settings);
  renderer.render_frame(0);
  std::vector<float2> hits(128 * 128);
  device().download(renderer.buffers()[BufferSlot::shade_hit], hits.data(), hits.size() * sizeof(float2));
  int missed = 0;
  for (const float2& h : hits) missed += PM_AS_INT(h.y) < 0;
  EXPECT_EQ(missed, 0) << "eye rays slipped through the edges between the room's triangles";
}

TEST(Extremes, DegenerateTrianglesAreInvisible) {
  const Scene clean = builtin_cornell_box();
  Scene s = clean;
  auto add = [&](Float3 a, Float3 b, Float3 c) {
    const uint32_t base = uint32_t(s.positions.size());
    s.positions.insert(s.positions.end(), {a, b, c});
    s.indices.insert(s.indices.end(), {base, base + 1, base + 2});
    s.triangle_material.push_back(0);
  };
  add({0.2f, 0.2f, 0.2f}, {0.2f, 0.2f, 0.2f}, {0.3f, 0.3f, 0.3f});  // repeated corner
  add({0.1f, 0.1f, 0.3f}, {0.2f, 0.2f, 0.3f}, {0.3f, 0.3f, 0.3f});  // collinear
  add({0.4f, 0.4f, 0.4f}, {0.4f, 0.4f, 0.4f}, {0.4f, 0.4f, 0.4f});  // a point
  add({0.0f, 0.3f, 0.3f}, {0.5f, 0.3f, 0.3f}, {0.25f, 0.3f, 0.3f});  // needle across the room
  const RenderSettings settings = photons(16384);
  const Rendered with = render(s, settings), without = render(clean, settings);
  expect_clean(with, "degenerate triangles");
  const std::vector<float>& a = with.image.find("direct")->rgb;
  const std::vector<float>& b = without.image.find("direct")->rgb;
  size_t differing = 0;
  for (size_t i = 0; i < a.size(); ++i) differing += std::fabs(a[i] - b[i]) > 1e-4f * (1.0f + b[i]);
  EXPECT_LE(differing, a.size() / 1000) << "degenerate triangles changed the direct light";
  EXPECT_NEAR(layer_mean(with.image, "indirect") / layer_mean(without.image, "indirect"), 1.0, 0.05);
}

TEST(Extremes, OnlyDegenerateTrianglesRenderBlack) {
  Scene s;
  s.name = "degenerate";
  s.materials = {MaterialDesc{}};
  s.positions = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
  s.indices = {0, 1, 2, 3, 4, 5};
  s.triangle_material = {0, 0};
  s.lights = {LightDesc{"l", {0, 1, 0}, {1, 1, 1}}};
  s.camera.position = {0, 1, -3};
  s.camera.look_at = {0, 0, 0};
  const Rendered r = render(s, photons(1000));
  expect_clean(r, "only degenerate triangles");
  EXPECT_EQ(layer_mean(r.image, ""), 0.0);
}

// --- photon counts ----------------------------------------------------------------------------

TEST(Extremes, FourBillionPhotonsRenderInBoundedMemory) {
  // 61035 passes of 65536 photons: 4e9 < 2^32, so the photons' random streams fit; memory is
  // sized by one pass, not by the total. (Only the set-up runs here: tracing 4e9 photons on PoCL
  // would take hours.)
  const Scene s = builtin_cornell_box();
  RenderSettings settings = photons(65536, 61035);
  settings.width = settings.height = 16;
  const uint64_t before = device().allocated_bytes();
  device().reset_peak();
  {
    Renderer renderer(device(), s, settings);
    ASSERT_NE(renderer.method(), nullptr);
    EXPECT_EQ(renderer.method()->work(61035).largest_pass, 65536.0);
    EXPECT_EQ(renderer.method()->work(61035).total, 65536.0 * 61035);
    EXPECT_LT(device().peak_allocated_bytes() - before, 256ull << 20);
  }
}

TEST(Extremes, PhotonsBeyond2To32PerFrameDrawTheirOwnRandomStreams) {
  // Photon i of pass k is photon k N + i of the frame, a 64-bit index: pass 65536 of 65536
  // photons starts at 2^32 and must not repeat pass 0's photons (a 32-bit index would wrap).
  const Scene s = builtin_cornell_box();
  RenderSettings settings = photons(65536);
  settings.width = settings.height = 24;
  Renderer renderer(device(), s, settings);
  auto pass_image = [&](uint32_t pass) {
    renderer.begin_frame(0);
    renderer.run_pass(pass);
    renderer.wait();
    return renderer.read_image().find("indirect")->rgb;
  };
  const std::vector<float> first = pass_image(0), wrapped = pass_image(65536), next = pass_image(1);
  EXPECT_NE(first, wrapped) << "pass 65536 traced pass 0's photons again";
  double a = 0, b = 0, c = 0;
  for (size_t i = 0; i < first.size(); ++i) {
    a += first[i];
    b += wrapped[i];
    c += next[i];
  }
  EXPECT_NEAR(b / a, 1.0, 0.1) << "the same distribution of photons";
  EXPECT_NEAR(c / a, 1.0, 0.1);
}

TEST(Extremes, APassTooLargeForItsHitRecordsIsRefused) {
  const Scene s = builtin_cornell_box();
  RenderSettings huge = photons(3000000000ull);
  try {
    Renderer renderer(device(), s, huge);
    ADD_FAILURE() << "a pass of 3e9 photons was accepted";
  } catch (const SettingError& e) {
    EXPECT_EQ(e.setting(), "photons") << e.what();
  }
}

TEST(Extremes, CommandLineRefusesTooManyPhotonsPerPassWithoutWritingAFile) {
  namespace fs = std::filesystem;
  const fs::path dir = test::process_temp_dir() / "pm_extremes_cli";
  fs::remove_all(dir);
  fs::create_directories(dir);
  // timeout: a build that accepted the count would start tracing 5e9 photons.
  const std::string cmd = "timeout 120 " + test::pmrender_binary() +
                          " render --backend opencl --photons 5000000000 --resolution 8x8 -o " +
                          (dir / "x.exr").string() + " >" + (dir / "out").string() + " 2>" + (dir / "err").string();
  const int status = std::system(cmd.c_str());
  std::ifstream in(dir / "err");
  std::stringstream err;
  err << in.rdbuf();
  EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2) << err.str();
  EXPECT_NE(err.str().find("--photons"), std::string::npos) << err.str();
  EXPECT_FALSE(fs::exists(dir / "x.exr"));
  fs::remove_all(dir);
}

// --- kernel functions at their limits (host) -------------------------------------------------------

TEST(ExtremesKernels, EmissionAtThePolesIsFiniteAndOrthonormal) {
  for (float u1 : {0.0f, 1e-30f, 1e-12f, 0.5f, 1.0f - 5.96e-8f, 1.0f}) {
    for (float u2 : {0.0f, 0.25f, 0.9999999f}) {
      PhotonRay ray;
      photon_emit_point(vec3(1e5f, -1e-3f, 0.0f), u1, u2, &ray);
      EXPECT_NEAR(vec3_length(ray.direction), 1.0f, 1e-5f) << u1;
      EXPECT_NEAR(vec3_length(ray.dd_u), 1.0f, 1e-5f) << u1;
      EXPECT_NEAR(vec3_length(ray.dd_v), 1.0f, 1e-5f) << u1;
      EXPECT_NEAR(vec3_dot(ray.direction, ray.dd_u), 0.0f, 1e-5f) << u1;
      EXPECT_NEAR(vec3_dot(ray.direction, ray.dd_v), 0.0f, 1e-5f) << u1;
    }
  }
}

TEST(ExtremesKernels, GrazingTransferAndDegenerateDifferentialsStayFinite) {
  // A photon travelling exactly along the plane it hits.
  Vec3 dp = photon_transfer_differential(vec3(0, 0, 0), vec3(0, 1, 0), vec3(1, 0, 0), 3.0f, vec3(0, 1, 0));
  EXPECT_TRUE(std::isfinite(dp.x) && std::isfinite(dp.y) && std::isfinite(dp.z));
  const float inf = INFINITY, nan = NAN;
  for (Vec3 d : {vec3(0, 0, 0), vec3(inf, 0, 0), vec3(nan, 1, 0), vec3(1e30f, 1e30f, 0), vec3(1e-38f, 0, 0)}) {
    for (float rmax : {1e-30f, 1e-3f, 1e30f}) {
      Footprint f = footprint_from_differentials(d, vec3(0, 0, 1e-3f), vec3(0, 1, 0), photon_spacing(1), 8.0f, rmax, 0);
      const float area = footprint_area(f);
      EXPECT_TRUE(std::isfinite(area) && area >= 0) << rmax;
      EXPECT_TRUE(std::isfinite(f.axis_u.x + f.axis_u.y + f.axis_u.z + f.axis_v.x + f.axis_v.y + f.axis_v.z));
      float r2 = 0;
      footprint_contains(f, vec3(0, 0, 0), vec3(1e-31f, 0, 0), &r2);
      EXPECT_FALSE(std::isnan(r2));
    }
  }
  EXPECT_TRUE(std::isfinite(photon_spacing(0)));
  EXPECT_TRUE(std::isfinite(photon_spacing(0xffffffffu)));
}

}  // namespace
}  // namespace pm
