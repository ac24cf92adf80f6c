// Textures and alpha masks rendered on PoCL. The camera pass: a checker on a floor under a point
// light, where every pixel's direct light over that of a white floor is the texel's linear
// albedo (and the albedo layer shows it). Every method: walls with a uniform texture render as
// walls of that colour without one, which proves the texture reaches the photon hits, the path
// vertices, the gather's shading points and the radiosity elements. Indirect light: photon
// mapping and the path tracer agree on a checkered room with a half-masked panel. Alpha masks:
// a masked-out half of a panel casts no shadow and shows the floor behind it, and a panel masked
// out everywhere renders as no panel for every method (exactly for the camera, photon and path
// methods; radiosity's link rays pass it too).
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <functional>
#include <memory>

#include "kernels/common/compat_host.h"
#include "kernels/common/texture.h"
#include "render/path/path_settings.h"
#include "render/renderer.h"
#include "render/scene_textures.h"
#include "render/scene_upload.h"
#include "support/device_checks.h"
#include "support/image_stats.h"
#include "support/render_settings.h"
#include "support/room_scenes.h"
#include "support/texture_images.h"

namespace pm {
namespace {

using Rgba = std::array<uint8_t, 4>;

// A width x height image whose texel (x, y) is texel(x, y), file channels 4.
uint32_t add_image(Scene& s, int width, int height, const std::function<Rgba(int, int)>& texel,
                   TextureWrap wrap = TextureWrap::clamp_to_edge) {
  TextureImage image;
  image.source = "test image " + std::to_string(s.images.size());
  image.width = width;
  image.height = height;
  image.file_channels = 4;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const Rgba t = texel(x, y);
      image.rgba.insert(image.rgba.end(), t.begin(), t.end());
    }
  s.images.push_back(image);
  s.textures.push_back(TextureRef{uint32_t(s.images.size() - 1), wrap, wrap});
  return uint32_t(s.textures.size() - 1);
}

// A quad (a, b, c, d) with texture coordinates (0, 0), (1, 0), (1, 1), (0, 1) at its corners.
void add_textured_quad(Scene& s, Float3 a, Float3 b, Float3 c, Float3 d, uint32_t material) {
  s.triangle_uvs.resize(3 * s.triangle_count());
  test::add_quad(s, a, b, c, d, material);
  s.triangle_uvs.insert(s.triangle_uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}});
}

const Rgba kTileA = {200, 100, 50, 255}, kTileB = {30, 180, 90, 255};

// 64 x 64 texels in 8 x 8 blocks of 8 x 8 texels, A and B alternating.
Rgba checker_texel(int x, int y) { return ((x / 8 + y / 8) % 2) ? kTileB : kTileA; }

// The floor [-1, 1]^2 in y = 0, texture coordinates u = (x + 1) / 2, v = (z + 1) / 2, a point light
// 2 m above its centre and a camera 3 m above looking down.
Scene checker_floor(bool textured) {
  Scene s;
  s.name = "checker-floor";
  s.source = "test";
  MaterialDesc floor = test::diffuse_material("floor", {1, 1, 1});
  if (textured) floor.base_color_texture = int(add_image(s, 64, 64, checker_texel));
  s.materials = {floor};
  add_textured_quad(s, {-1, 0, -1}, {1, 0, -1}, {1, 0, 1}, {-1, 0, 1}, 0);
  s.lights = {LightDesc{"lamp", {0, 2, 0}, {10, 10, 10}}};
  s.camera.position = {0, 3, 0};
  s.camera.look_at = {0, 0, 0};
  s.camera.up = {0, 0, 1};
  s.camera.vertical_fov_degrees = 35;
  return s;
}

TEST(TextureRender, CameraPassDirectLightAndAlbedoLayerShowTheTexelsAlbedos) {
  Device& device = test::shared_opencl_device();
  RenderSettings settings;  // direct light only
  settings.width = settings.height = 48;
  settings.layers = parse_film_layers("albedo,position");
  const Scene textured = checker_floor(true), white = checker_floor(false);
  Renderer textured_renderer(device, textured, settings);
  const FrameImage image = textured_renderer.render_frame(0);
  Renderer white_renderer(device, white, settings);
  const FrameImage reference = white_renderer.render_frame(0);
  EXPECT_EQ(textured_renderer.texture_bytes(), 64u * 64u * 4u + 16u + 2u * 32u + 256u * 4u);
  EXPECT_EQ(white_renderer.texture_bytes(), 0u);

  DeviceTextures host;
  pack_texture_images(textured, &host);
  const std::vector<float>& direct = image.find("direct")->rgb;
  const std::vector<float>& lit = reference.find("direct")->rgb;
  const std::vector<float>& albedo = image.find("albedo")->rgb;
  const DataLayer* position = image.find_data("P");
  ASSERT_NE(position, nullptr);
  size_t pure[2] = {0, 0};
  for (size_t i = 0; i < direct.size() / 3; ++i) {
    const float u = (position->values[3 * i] + 1) / 2, v = (position->values[3 * i + 2] + 1) / 2;
    ASSERT_GT(lit[3 * i + 1], 0.0f) << "pixel " << i << " sees no lit floor";
    // Every pixel, blends across tile edges included: the host's lookup at the pixel's point.
    const float4 t = texture_sample(host.info.data(), host.texels.data(), host.srgb_table.data(), 0, u, v, 1);
    const float expected[3] = {t.x, t.y, t.z};
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(direct[3 * i + c] / lit[3 * i + c], expected[c], 2e-3) << "pixel " << i << " channel " << c;
      EXPECT_NEAR(albedo[3 * i + c], expected[c], 2e-3) << "pixel " << i << " channel " << c;
    }
    // Well inside a tile (more than a texel from its edges) the ratio is the tile's texel exactly.
    const float bu = u * 8, bv = v * 8;
    const auto inside = [](float b) { return std::fabs(b - std::round(b)) > 0.125f; };
    if (!inside(bu) || !inside(bv)) continue;
    const int tile = (int(bu) + int(bv)) % 2;
    const Rgba& texel = tile ? kTileB : kTileA;
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(direct[3 * i + c] / lit[3 * i + c] / test::srgb_to_linear(texel[size_t(c)]), 1.0, 1e-4)
          << "pixel " << i << " channel " << c;
    ++pure[tile];
  }
  EXPECT_GT(pure[0], 300u);
  EXPECT_GT(pure[1], 300u);
}

// The closed room (tests/support/room_scenes.h) with its two materials either as plain colours
// or as white materials times a one-texel texture of those colours (texture coordinates (0, 0)).
Scene uniformly_textured_room(bool textured) {
  Scene s = test::closed_room();
  const Rgba codes[2] = {{214, 214, 214, 255}, {220, 124, 108, 255}};
  for (size_t m = 0; m < 2; ++m) {
    if (textured) {
      s.materials[m].diffuse = {1, 1, 1};
      s.materials[m].base_color_texture = int(add_image(s, 1, 1, [&](int, int) { return codes[m]; }));
    } else {
      // The very floats the device's lookup gives.
      s.materials[m].diffuse = {srgb_code_to_linear(codes[m][0]), srgb_code_to_linear(codes[m][1]),
                                srgb_code_to_linear(codes[m][2])};
    }
  }
  return s;
}

RenderSettings method_settings(const std::string& method) {
  RenderSettings settings;
  if (method == "photon") {
    PhotonSettings photons;
    photons.photons = 16384;
    settings = test::photon_render_settings(photons);
  } else if (method == "path") {
    auto path = std::make_shared<PathSettings>();
    path->samples = 4;
    settings.method = path;
  } else if (method == "radiosity") {
    RadiositySettings radiosity;  // coarse: the comparison needs no accuracy, only the same work
    radiosity.directions = 64;
    radiosity.max_edge = 0.5f;
    settings = test::radiosity_render_settings(radiosity);
  }
  settings.width = 32;
  settings.height = 24;
  return settings;
}

class UniformTexture : public ::testing::TestWithParam<std::string> {};

TEST_P(UniformTexture, RendersAsItsColourWithoutATexture) {
  Device& device = test::shared_opencl_device();
  const RenderSettings settings = method_settings(GetParam());
  const Scene textured = uniformly_textured_room(true), plain = uniformly_textured_room(false);
  Renderer a(device, textured, settings);
  const FrameImage with = a.render_frame(0);
  Renderer b(device, plain, settings);
  const FrameImage without = b.render_frame(0);
  for (const char* layer : {"direct", "indirect"}) {
    const test::ImageDifference d = test::compare_rgb(with.find(layer)->rgb, without.find(layer)->rgb);
    std::printf("%s, %s: mean relative difference %.3g (mean %.4g)\n", GetParam().c_str(), layer, d.mean_relative,
                d.mean_value);
    EXPECT_GT(d.mean_value, 0.0) << layer;
    // The lookup's rounding (a bilinear blend of equal texels) may differ from the colour by an
    // ulp, which can flip a rare Russian roulette decision; no more.
    EXPECT_LT(d.mean_relative, 1e-4) << layer;
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, UniformTexture, ::testing::Values("photon", "path", "radiosity"));

// A material masked by a 64 x 1 alpha texture: alpha 0 where u < 0.5, 255 from there on.
MaterialDesc half_masked(Scene& s, const char* name) {
  MaterialDesc m = test::diffuse_material(name, {0.5f, 0.5f, 0.5f});
  m.alpha_mask = true;
  m.alpha_texture = int(add_image(s, 64, 1, [](int x, int) { return Rgba{255, 255, 255, uint8_t(x < 32 ? 0 : 255)}; }));
  m.alpha_channel = 3;
  m.alpha_cutoff = 0.5f;
  return m;
}

TEST(TextureRender, MaskedOutHalfCastsNoShadowAndShowsTheFloorBehind) {
  // A large floor in y = 0, a 1 x 1 m panel 1 m above it (u = x + 0.5, its hole where x < 0), a
  // light 0.5 m above the panel (its shadow three times its size, mostly beside what the panel
  // hides from the camera), the camera 6 m up looking down through the panel.
  Scene s;
  s.name = "masked-panel";
  s.source = "test";
  s.materials = {test::diffuse_material("floor", {0.8f, 0.8f, 0.8f})};
  s.materials.push_back(half_masked(s, "panel"));
  add_textured_quad(s, {-3, 0, -3}, {3, 0, -3}, {3, 0, 3}, {-3, 0, 3}, 0);
  add_textured_quad(s, {-0.5f, 1, -0.5f}, {0.5f, 1, -0.5f}, {0.5f, 1, 0.5f}, {-0.5f, 1, 0.5f}, 1);
  const Float3 light{0, 1.5f, 0}, eye{0, 6, 0};
  s.lights = {LightDesc{"lamp", light, {20, 20, 20}}};
  s.camera.position = eye;
  s.camera.look_at = {0, 0, 0};
  s.camera.up = {0, 0, 1};
  s.camera.vertical_fov_degrees = 50;
  RenderSettings settings;
  settings.width = settings.height = 64;
  settings.layers = parse_film_layers("position");
  Renderer renderer(test::shared_opencl_device(), s, settings);
  const FrameImage image = renderer.render_frame(0);
  const std::vector<float>& direct = image.find("direct")->rgb;
  const std::vector<float>& p = image.find_data("P")->values;
  // Where a line from a to b crosses the panel's plane y = 1, as the panel's u.
  const auto crossing = [](Float3 a, Float3 b, float* u, float* z) {
    const float t = (1 - a.y) / (b.y - a.y);
    *u = a.x + t * (b.x - a.x) + 0.5f;
    *z = a.z + t * (b.z - a.z);
  };
  size_t shadowed = 0, lit_through_hole = 0, seen_through_hole = 0;
  for (size_t i = 0; i < direct.size() / 3; ++i) {
    const Float3 hit{p[3 * i], p[3 * i + 1], p[3 * i + 2]};
    float u, z;
    if (std::fabs(hit.y - 1) < 1e-3f) {
      EXPECT_GT(hit.x, -0.02f) << "pixel " << i << " hit the panel's hole";  // the blend reaches half a texel
      continue;
    }
    ASSERT_NEAR(hit.y, 0.0f, 1e-3f) << "pixel " << i;
    crossing(eye, hit, &u, &z);
    if (std::fabs(z) < 0.48f && u > 0.02f && u < 0.45f) ++seen_through_hole;
    crossing(hit, light, &u, &z);
    const bool under_panel = std::fabs(z) < 0.48f && u > 0.02f && u < 0.98f;
    if (under_panel && u > 0.55f) {
      EXPECT_EQ(direct[3 * i], 0.0f) << "pixel " << i << ": the opaque half casts a shadow";
      ++shadowed;
    } else if (under_panel && u < 0.45f) {
      EXPECT_GT(direct[3 * i], 0.0f) << "pixel " << i << ": light passes the masked-out half";
      ++lit_through_hole;
    }
  }
  EXPECT_GT(shadowed, 50u);
  EXPECT_GT(lit_through_hole, 50u);
  EXPECT_GT(seen_through_hole, 50u);
}

// The closed room with two panels masked out everywhere (alpha 0): 3 x 4 m, 0.7 m under the
// light, and 3 x 2 m standing on the floor (where footprint clipping would see it as a wall).
Scene room_with_invisible_panel(bool panel) {
  Scene s = test::closed_room();
  if (!panel) return s;
  MaterialDesc invisible = test::diffuse_material("invisible", {0.5f, 0.5f, 0.5f});
  invisible.alpha_mask = true;
  invisible.alpha_texture = int(add_image(s, 2, 2, [](int, int) { return Rgba{255, 255, 255, 0}; }));
  s.materials.push_back(invisible);
  add_textured_quad(s, {0.5f, 1.5f, 0.5f}, {3.5f, 1.5f, 0.5f}, {3.5f, 1.5f, 4.5f}, {0.5f, 1.5f, 4.5f},
                    uint32_t(s.materials.size() - 1));
  add_textured_quad(s, {0.5f, 0, 3}, {3.5f, 0, 3}, {3.5f, 2, 3}, {0.5f, 2, 3}, uint32_t(s.materials.size() - 1));
  return s;
}

class InvisiblePanel : public ::testing::TestWithParam<std::string> {};

TEST_P(InvisiblePanel, RendersAsNoPanel) {
  Device& device = test::shared_opencl_device();
  RenderSettings settings = method_settings(GetParam());
  // The automatic smoothing and leaf size follow the scene's surface area, which the panel adds to.
  if (GetParam() == "photon") {
    PhotonSettings& photons = test::edit_photons(settings);
    photons.smoothing = 8.0f;
    photons.leaf_threshold = 8;
  }
  const Scene with = room_with_invisible_panel(true), without = room_with_invisible_panel(false);
  Renderer a(device, with, settings);
  const FrameImage masked = a.render_frame(0);
  Renderer b(device, without, settings);
  const FrameImage absent = b.render_frame(0);
  for (const char* layer : {"direct", "indirect"}) {
    const test::ImageDifference d = test::compare_rgb(masked.find(layer)->rgb, absent.find(layer)->rgb);
    std::printf("%s, %s: mean relative difference %.3g (mean %.4g)\n", GetParam().c_str(), layer, d.mean_relative,
                d.mean_value);
    EXPECT_GT(d.mean_value, 0.0) << layer;
    // The same rays hit the same triangles; only the BVH around them differs, and with it which
    // of two triangles a ray exactly on their shared edge reports first (measured: photon
    // indirect 3e-10, everything else 0; photon footprints clipped at the standing panel: 0.9 %).
    // Radiosity draws each element's link directions by its index, and the panels' elements
    // move the room's in the element order: other directions, 2.6 % per pixel. Opaque, the
    // panel under the light alone changes the indirect light by more than 60 % per pixel.
    const bool other_directions = GetParam() == "radiosity" && std::string(layer) == "indirect";
    EXPECT_LT(d.mean_relative, other_directions ? 0.05 : 1e-4) << layer;
  }
}

INSTANTIATE_TEST_SUITE_P(Methods, InvisiblePanel, ::testing::Values("photon", "path", "radiosity"));

// The closed room with its white walls, floor and ceiling as a checker of light and dark tiles
// (four tiles a side on every quad) and a half-masked panel under the light: photons and paths
// must meet the same texels and pass the same holes.
Scene checkered_room() {
  Scene s = test::closed_room();
  s.triangle_uvs.clear();
  for (size_t q = 0; q < s.triangle_count() / 2; ++q)
    s.triangle_uvs.insert(s.triangle_uvs.end(), {{0, 0}, {1, 0}, {1, 1}, {0, 0}, {1, 1}, {0, 1}});
  s.materials[0].diffuse = {1, 1, 1};
  s.materials[0].base_color_texture = int(add_image(
      s, 32, 32, [](int x, int y) { return ((x / 8 + y / 8) % 2) ? Rgba{235, 235, 225, 255} : Rgba{70, 80, 90, 255}; },
      TextureWrap::repeat));
  s.materials.push_back(half_masked(s, "panel"));
  add_textured_quad(s, {1.0f, 1.6f, 1.5f}, {3.0f, 1.6f, 1.5f}, {3.0f, 1.6f, 3.5f}, {1.0f, 1.6f, 3.5f},
                    uint32_t(s.materials.size() - 1));
  return s;
}

TEST(TextureRender, PhotonMappingAndPathTracingAgreeInACheckeredRoom) {
  Device& device = test::shared_opencl_device();
  const Scene room = checkered_room();
  auto path = std::make_shared<PathSettings>();
  path->samples = 64;
  RenderSettings traced_settings;
  traced_settings.method = path;
  traced_settings.passes = 2;
  PhotonSettings photons;
  photons.photons = 65536;
  RenderSettings mapped_settings = test::photon_render_settings(photons, 8);
  for (RenderSettings* s : {&traced_settings, &mapped_settings}) {
    s->width = 24;
    s->height = 18;
  }
  Renderer traced_renderer(device, room, traced_settings);
  const FrameImage traced = traced_renderer.render_frame(0);
  Renderer mapped_renderer(device, room, mapped_settings);
  const FrameImage mapped = mapped_renderer.render_frame(0);
  const double traced_mean = test::mean(traced.find("indirect")->rgb);
  const double mapped_mean = test::mean(mapped.find("indirect")->rgb) + test::mean(mapped.find("caustic")->rgb);
  std::printf("checkered room: indirect mean path %.5g, photon %.5g, ratio %.4f\n", traced_mean, mapped_mean,
              mapped_mean / traced_mean);
  // Measured over seeds 1-5: ratio 0.985-1.013; the path tracer's mean varies by 1.2 % (one
  // sigma), the photon mapper's by 0.1 %; in the untextured room the photon mapper reads 2.5 %
  // low. 5 % is four sigma; an albedo missed at the photon hits or the path vertices (white
  // instead of the checker, whose mean is about half) would double the indirect light.
  EXPECT_NEAR(mapped_mean / traced_mean, 1.0, 0.05);
}

// Renderers of one scene may share its host-side upload (render/scene_upload.h, as --method
// auto's candidates do): the BVH, textures and materials prepared once render what a renderer
// that prepared its own renders, to the bit.
TEST(TextureRender, ASharedSceneUploadRendersAsAnOwnOne) {
  Device& device = test::shared_opencl_device();
  const Scene scene = checkered_room();
  PhotonSettings photons;
  photons.photons = 20000;
  RenderSettings settings = test::photon_render_settings(photons);
  settings.width = 24;
  settings.height = 18;
  StepClock clock;
  std::vector<StartupStep> steps;
  const std::shared_ptr<const SceneUpload> upload = prepare_scene_upload(scene, clock, &steps);
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_FALSE(upload->textures.texels.empty());
  Renderer own(device, scene, settings), shared(device, scene, settings, upload), again(device, scene, settings, upload);
  auto step = [](const Renderer& r) {
    for (const StartupStep& s : r.setup_steps())
      if (s.name == "BVH build") return s.detail;
    return std::string();
  };
  EXPECT_EQ(step(shared), "shared with the renderers of this scene");
  EXPECT_NE(step(own), step(shared));
  EXPECT_EQ(shared.texture_bytes(), own.texture_bytes());
  const FrameImage a = own.render_frame(0), b = shared.render_frame(0), c = again.render_frame(0);
  for (const char* layer : {"", "direct", "indirect"}) {
    EXPECT_GT(test::mean(a.find(layer)->rgb), 0.0) << layer;
    EXPECT_TRUE(a.find(layer)->rgb == b.find(layer)->rgb) << "layer '" << layer << "'";
    EXPECT_TRUE(a.find(layer)->rgb == c.find(layer)->rgb) << "layer '" << layer << "'";
  }
}

}  // namespace
}  // namespace pm
