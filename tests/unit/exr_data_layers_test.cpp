// Tests of data layers (normals, depth, positions, ids) in render/exr_io: their channel names and
// pixel types as OpenEXR itself lists them, values read back through read_exr in half and float
// files, ids exact as 32-bit floats inside half files, the depth of a miss clamped into half, the
// NaN guard and malformed data layers, and files without data layers keeping their channel list.
#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>

#include <cmath>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "render/errors.h"
#include "render/exr_io.h"
#include "support/test_folder.h"

namespace pm {
namespace {

class ExrDataLayers : public test::FolderTest {
 protected:
  ExrDataLayers() : FolderTest("pm_exr_data_layers_" + std::to_string(::getpid()) + "_") {}
};

// A 3 x 2 image: the combined layer, a normal layer N (X, Y, Z), a bare Z with one miss and a
// float-only id layer holding integers half cannot hold exactly.
FrameImage image_with_data_layers() {
  FrameImage image;
  image.width = 3;
  image.height = 2;
  image.layers.push_back(ImageLayer{"", std::vector<float>(18, 0.5f)});
  DataLayer normal{"N", {"X", "Y", "Z"}, {}, false};
  for (int i = 0; i < 6; ++i) normal.values.insert(normal.values.end(), {0.0f, 0.6f, -0.8f});
  DataLayer depth{"", {"Z"}, {1.5f, 2.25f, 3.0f, 1e10f, 4.0f, 5.5f}, false};
  DataLayer ids{"object_id", {"X"}, {0.0f, 1.0f, 2049.0f, -1.0f, 65537.0f, 16777216.0f}, true};
  image.data_layers = {normal, depth, ids};
  return image;
}

// Channel name -> pixel type, as OpenEXR reads the header.
std::map<std::string, Imf::PixelType> channel_types(const std::string& path) {
  Imf::InputFile file(path.c_str());
  std::map<std::string, Imf::PixelType> types;
  for (auto it = file.header().channels().begin(); it != file.header().channels().end(); ++it)
    types[it.name()] = it.channel().type;
  return types;
}

TEST_F(ExrDataLayers, ChannelNamesAndTypesFollowThePixelTypeExceptIds) {
  const std::string path = (dir_ / "half.exr").string();
  write_exr(path, image_with_data_layers(), false);
  const std::map<std::string, Imf::PixelType> expected = {
      {"B", Imf::HALF},   {"G", Imf::HALF},   {"R", Imf::HALF}, {"N.X", Imf::HALF},         {"N.Y", Imf::HALF},
      {"N.Z", Imf::HALF}, {"Z", Imf::HALF},   {"object_id.X", Imf::FLOAT}};
  EXPECT_EQ(channel_types(path), expected);

  write_exr(path, image_with_data_layers(), true);
  for (const auto& [name, type] : channel_types(path)) EXPECT_EQ(type, Imf::FLOAT) << name;
}

TEST_F(ExrDataLayers, HalfFilesKeepIdsExactAndClampTheMissDepth) {
  const std::string path = (dir_ / "half.exr").string();
  write_exr(path, image_with_data_layers(), false);
  const FrameImage back = read_exr(path);
  ASSERT_EQ(back.data_layers.size(), 3u);  // "" (Z), N, object_id in channel-list order
  const DataLayer* depth = back.find_data("");
  ASSERT_NE(depth, nullptr);
  EXPECT_EQ(depth->channels, std::vector<std::string>{"Z"});
  EXPECT_EQ(depth->values, (std::vector<float>{1.5f, 2.25f, 3.0f, 65504.0f, 4.0f, 5.5f}));
  EXPECT_FALSE(depth->full_float);
  const DataLayer* normal = back.find_data("N");
  ASSERT_NE(normal, nullptr);
  EXPECT_EQ(normal->channels, (std::vector<std::string>{"X", "Y", "Z"}));
  for (size_t i = 0; i < normal->values.size(); i += 3) {
    EXPECT_EQ(normal->values[i], 0.0f);
    EXPECT_NEAR(normal->values[i + 1], 0.6f, 1e-3f);
    EXPECT_NEAR(normal->values[i + 2], -0.8f, 1e-3f);
  }
  const DataLayer* ids = back.find_data("object_id");
  ASSERT_NE(ids, nullptr);
  EXPECT_TRUE(ids->full_float);
  EXPECT_EQ(ids->values, image_with_data_layers().data_layers[2].values);  // 2049 and 65537 too
  // The combined layer is read as before, and it is the only colour layer.
  ASSERT_EQ(back.layers.size(), 1u);
  EXPECT_EQ(back.layers[0].name, "");
}

TEST_F(ExrDataLayers, FloatFilesKeepEveryValue) {
  const std::string path = (dir_ / "float.exr").string();
  const FrameImage image = image_with_data_layers();
  write_exr(path, image, true);
  const FrameImage back = read_exr(path);
  EXPECT_EQ(back.find_data("")->values, image.data_layers[1].values);  // 1e10 for the miss
  EXPECT_EQ(back.find_data("N")->values, image.data_layers[0].values);
  EXPECT_TRUE(back.find_data("N")->full_float);
}

TEST_F(ExrDataLayers, NonFiniteDataIsRefusedNamingTheChannel) {
  FrameImage image = image_with_data_layers();
  image.data_layers[0].values[4] = std::nanf("");
  const std::string path = (dir_ / "nan.exr").string();
  try {
    write_exr(path, image, true);
    ADD_FAILURE() << "written";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("channel 'N.Y' pixel (1, 0)"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST_F(ExrDataLayers, MalformedDataLayersAreRefused) {
  const std::string path = (dir_ / "bad.exr").string();
  FrameImage short_layer = image_with_data_layers();
  short_layer.data_layers[0].values.pop_back();
  EXPECT_THROW(write_exr(path, short_layer, false), DeviceError);
  FrameImage clash = image_with_data_layers();
  clash.data_layers.push_back(DataLayer{"", {"R"}, std::vector<float>(6, 0.0f), false});  // R is the combined's
  EXPECT_THROW(write_exr(path, clash, false), DeviceError);
  EXPECT_FALSE(std::filesystem::exists(path));
}

TEST_F(ExrDataLayers, ImagesWithoutDataLayersWriteOnlyTheirColourChannels) {
  FrameImage image = image_with_data_layers();
  image.data_layers.clear();
  image.layers.push_back(ImageLayer{"direct", std::vector<float>(18, 0.25f)});
  const std::string path = (dir_ / "plain.exr").string();
  write_exr(path, image, false);
  std::vector<std::string> names;
  for (const auto& [name, type] : channel_types(path)) names.push_back(name);
  EXPECT_EQ(names, (std::vector<std::string>{"B", "G", "R", "direct.B", "direct.G", "direct.R"}));
  EXPECT_TRUE(read_exr(path).data_layers.empty());
}

}  // namespace
}  // namespace pm
