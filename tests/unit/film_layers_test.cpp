// Tests of the film's extra layers on the host: the film_layers stage function after the camera
// pass against hand-computed albedo, normal, depth, position and ids (tests/support/layer_scene.h),
// through a mirror to the first non-specular surface and without mirror bounces; the --layers
// names; their channels in a FrameImage; the header attributes that list them.
#include <gtest/gtest.h>

#include <map>
#include <string>
#include <vector>

#include "kernels/common/compat_host.h"
#include "kernels/common/film_layers.h"
#include "render/errors.h"
#include "render/film_layers.h"
#include "support/host_render.h"
#include "support/layer_scene.h"

namespace pm {
namespace {

struct HostLayers {
  std::vector<float4> albedo, normal, position;
};

// The camera pass and the film_layers stage, run on the host pixel by pixel.
HostLayers film_layers_on_host(const Scene& scene, int width, int height, int mirror_depth) {
  test::HostCameraPass pass(scene, width, height, mirror_depth);
  HostLayers out{std::vector<float4>(pass.pixels), std::vector<float4>(pass.pixels), std::vector<float4>(pass.pixels)};
  pass.kg.film_albedo = out.albedo.data();
  pass.kg.film_normal = out.normal.data();
  pass.kg.film_position = out.position.data();
  pass.run();
  for (uint32_t i = 0; i < uint32_t(pass.pixels); ++i) kernel_film_layers(&pass.kg, &pass.p, i);
  return out;
}

void expect_pixel(const HostLayers& got, size_t i, const test::ExpectedLayers& e) {
  const float tolerance = 1e-5f;
  EXPECT_NEAR(got.albedo[i].x, e.albedo[0], tolerance);
  EXPECT_NEAR(got.albedo[i].y, e.albedo[1], tolerance);
  EXPECT_NEAR(got.albedo[i].z, e.albedo[2], tolerance);
  EXPECT_NEAR(got.normal[i].x, e.normal[0], tolerance);
  EXPECT_NEAR(got.normal[i].y, e.normal[1], tolerance);
  EXPECT_NEAR(got.normal[i].z, e.normal[2], tolerance);
  EXPECT_NEAR(got.normal[i].w, e.depth, tolerance * e.depth);
  EXPECT_NEAR(got.position[i].x, e.position[0], tolerance);
  EXPECT_NEAR(got.position[i].y, e.position[1], tolerance);
  EXPECT_NEAR(got.position[i].z, e.position[2], tolerance);
  EXPECT_EQ(PM_AS_INT(got.position[i].w), int(e.object_id));
  EXPECT_EQ(PM_AS_INT(got.albedo[i].w), int(e.material_id));
}

void expect_scene_layers(int mirror_depth) {
  const int width = 16, height = 12;
  const HostLayers got = film_layers_on_host(test::layer_scene(width, height), width, height, mirror_depth);
  int mirror = 0, plane = 0, miss = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      SCOPED_TRACE("pixel " + std::to_string(x) + ", " + std::to_string(y));
      const test::ExpectedLayers e = test::expected_layers(x, y, width, height, mirror_depth);
      mirror += e.object_id == test::kLayerMirror;
      plane += e.object_id == test::kLayerPlane;
      miss += e.object_id < 0;
      expect_pixel(got, size_t(y) * width + x, e);
    }
  EXPECT_EQ(mirror, width * height / 2);  // the scene shows all three cases
  EXPECT_EQ(plane, width * height / 4);
  EXPECT_EQ(miss, width * height / 4);
}

TEST(FilmLayers, ThroughAMirrorToTheFirstNonSpecularSurface) { expect_scene_layers(1); }

TEST(FilmLayers, APathEndingAtAMirrorHasNoAlbedoOrNormal) { expect_scene_layers(0); }

TEST(FilmLayers, NamesParseAndPrintInFileOrder) {
  EXPECT_TRUE(parse_film_layers("").empty());
  EXPECT_TRUE(parse_film_layers("none").empty());
  const FilmLayers all = parse_film_layers("all");
  EXPECT_EQ(film_layers_text(all), "albedo,normal,depth,position,object_id,material_id");
  const FilmLayers some = parse_film_layers("depth, albedo,depth");
  EXPECT_TRUE(some.has(FilmLayer::depth) && some.has(FilmLayer::albedo));
  EXPECT_FALSE(some.has(FilmLayer::normal));
  EXPECT_EQ(film_layers_text(some), "albedo,depth");
  EXPECT_EQ(parse_film_layers(film_layers_text(some)), some);
}

TEST(FilmLayers, UnknownNamesAreSettingErrorsNamingTheValue) {
  for (const char* bad : {"foo", "albedo,foo", "Albedo", "albedo,", "none,depth", "normals"}) {
    SCOPED_TRACE(bad);
    try {
      parse_film_layers(bad);
      ADD_FAILURE() << "accepted";
    } catch (const SettingError& e) {
      EXPECT_EQ(e.setting(), "layers");
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(FilmLayers, ReadBackBecomesNamedChannels) {
  FrameImage image;
  image.width = 2;
  image.height = 1;
  const std::vector<float4> albedo = {{0.5f, 0.25f, 0.125f, PM_AS_FLOAT(7)}, {0, 0, 0, PM_AS_FLOAT(-1)}};
  const std::vector<float4> normal = {{0, 0, 1, 2.5f}, {0, 0, 0, 1e10f}};
  const std::vector<float4> position = {{1, 2, -2.5f, PM_AS_FLOAT(16777216)}, {0, 0, 0, PM_AS_FLOAT(-1)}};
  add_film_layers(image, parse_film_layers("all"), albedo, normal, position);

  const ImageLayer* albedo_layer = image.find("albedo");
  ASSERT_NE(albedo_layer, nullptr);
  EXPECT_EQ(albedo_layer->rgb, (std::vector<float>{0.5f, 0.25f, 0.125f, 0, 0, 0}));
  std::vector<std::string> channels;
  for (const DataLayer& layer : image.data_layers)
    for (size_t c = 0; c < layer.channels.size(); ++c) channels.push_back(layer.channel_name(c));
  EXPECT_EQ(channels, (std::vector<std::string>{"N.X", "N.Y", "N.Z", "Z", "P.X", "P.Y", "P.Z", "object_id.X",
                                                 "material_id.X"}));
  ASSERT_NE(image.find_data(""), nullptr);
  EXPECT_EQ(image.find_data("")->values, (std::vector<float>{2.5f, 1e10f}));
  EXPECT_FALSE(image.find_data("")->full_float);  // depth follows the file's pixel type
  const DataLayer* object = image.find_data("object_id");
  ASSERT_NE(object, nullptr);
  EXPECT_TRUE(object->full_float);
  EXPECT_EQ(object->values, (std::vector<float>{16777216.0f, -1.0f}));  // exact integers, -1: miss
  EXPECT_EQ(image.find_data("material_id")->values, (std::vector<float>{7.0f, -1.0f}));
}

TEST(FilmLayers, NoLayersAddNothing) {
  FrameImage image;
  image.width = 1;
  image.height = 1;
  const std::vector<float4> one(1);
  add_film_layers(image, FilmLayers{}, one, one, one);
  EXPECT_TRUE(image.layers.empty());
  EXPECT_TRUE(image.data_layers.empty());
  EXPECT_TRUE(film_layer_attributes(FilmLayers{}, test::layer_scene(4, 4), true).empty());
}

TEST(FilmLayers, HeaderAttributesListLayersChannelsAndIds) {
  const Scene scene = test::layer_scene(4, 4);
  std::map<std::string, std::string> half, full;
  for (auto& [name, value] : film_layer_attributes(parse_film_layers("all"), scene, false)) half[name] = value;
  for (auto& [name, value] : film_layer_attributes(parse_film_layers("depth,object_id"), scene, true)) full[name] = value;
  EXPECT_EQ(half["pmrender/layers"],
            "albedo:albedo.R,albedo.G,albedo.B normal:N.X,N.Y,N.Z depth:Z position:P.X,P.Y,P.Z "
            "object_id:object_id.X material_id:material_id.X");
  EXPECT_EQ(half["pmrender/depth_miss"], "65504");  // what a half file can hold
  EXPECT_EQ(full["pmrender/depth_miss"], "1e+10");
  EXPECT_EQ(half["pmrender/object_ids"], "0=plane; 1=mirror; 2=wall");
  EXPECT_EQ(half["pmrender/material_ids"], "0=plane; 1=mirror; 2=wall");
  EXPECT_EQ(full["pmrender/layers"], "depth:Z object_id:object_id.X");
  EXPECT_EQ(full.count("pmrender/material_ids"), 0u);
}

TEST(FilmLayers, TrianglesAddedWithoutAnObjectFormOneMore) {
  Scene scene = test::layer_scene(4, 4);
  const uint32_t base = uint32_t(scene.positions.size());
  scene.positions.insert(scene.positions.end(), {{0, 0, -5}, {1, 0, -5}, {0, 1, -5}});
  scene.indices.insert(scene.indices.end(), {base, base + 1, base + 2});
  scene.triangle_material.push_back(0);  // no triangle_object entry, as a program extending a scene writes it
  const SceneBvh bvh = build_scene_bvh(scene);
  for (size_t i = 0; i < bvh.triangle_count(); ++i) {
    const uint32_t original = bvh.original_index[i];
    EXPECT_EQ(PM_AS_INT(bvh.triangles[3 * i + 2].w), original < 6 ? int(scene.triangle_object[original]) : 3);
  }
  std::map<std::string, std::string> a;
  for (auto& [name, value] : film_layer_attributes(parse_film_layers("object_id"), scene, true)) a[name] = value;
  EXPECT_EQ(a["pmrender/object_ids"], "0=plane; 1=mirror; 2=wall; 3=unnamed");
  scene.triangle_object.resize(9, 0);  // more entries than triangles: a broken scene
  EXPECT_THROW(build_scene_bvh(scene), InputError);
}

}  // namespace
}  // namespace pm
