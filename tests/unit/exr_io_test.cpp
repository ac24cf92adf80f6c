// Tests of render/exr_io: half and float round trips, layers and attributes, the NaN guard, the
// atomic write (no temporaries left, existing targets replaced by rename), error kinds and
// messages, and exr_is_complete on truncated files. Files go to a fresh folder per test.
#include "render/exr_io.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfCompression.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfInputFile.h>
#include <OpenEXR/ImfOutputFile.h>
#include <Imath/half.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "render/errors.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

// A width x height image with the given layers, filled with seeded random values in [0, scale).
FrameImage random_image(int width, int height, const std::vector<std::string>& layer_names,
                        float scale = 4.0f, unsigned seed = 1) {
  std::mt19937 generator(seed);
  std::uniform_real_distribution<float> distribution(0.0f, scale);
  FrameImage image;
  image.width = width;
  image.height = height;
  for (const std::string& name : layer_names) {
    ImageLayer& layer = image.layers.emplace_back();
    layer.name = name;
    layer.rgb.resize(size_t(width) * height * 3);
    for (float& value : layer.rgb) value = distribution(generator);
  }
  return image;
}

std::vector<char> read_bytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<char>(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const fs::path& path, const std::vector<char>& bytes) {
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), std::streamsize(bytes.size()));
}

class ExrIoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const std::string test_name =
        ::testing::UnitTest::GetInstance()->current_test_info()->name();
    folder_ = fs::path(::testing::TempDir()) /
              ("pm_exr_io_test_" + std::to_string(::getpid()) + "_" + test_name);
    fs::remove_all(folder_);
    fs::create_directories(folder_);
  }
  void TearDown() override {
    std::error_code ignored;
    fs::remove_all(folder_, ignored);
  }

  // Every file and folder under the test folder, relative and sorted, hidden ones included.
  std::vector<std::string> entries() const {
    std::vector<std::string> names;
    for (const auto& entry : fs::recursive_directory_iterator(folder_)) {
      names.push_back(fs::relative(entry.path(), folder_).string());
    }
    std::sort(names.begin(), names.end());
    return names;
  }

  std::string path(const std::string& name) const { return (folder_ / name).string(); }

  fs::path folder_;
};

TEST_F(ExrIoTest, HalfRoundTripKeepsValuesWithinHalfPrecision) {
  FrameImage image = random_image(19, 7, {""}, 1000.0f);
  image.layers[0].rgb[0] = 0.0f;
  image.layers[0].rgb[1] = 1e-3f;
  const std::string file = path("half.exr");
  write_exr(file, image, /*full_float=*/false);

  Imf::InputFile raw(file.c_str());
  EXPECT_EQ(raw.header().compression(), Imf::ZIP_COMPRESSION);
  ASSERT_NE(raw.header().channels().findChannel("G"), nullptr);
  EXPECT_EQ(raw.header().channels().findChannel("G")->type, Imf::HALF);

  const FrameImage back = read_exr(file);
  ASSERT_EQ(back.width, 19);
  ASSERT_EQ(back.height, 7);
  const ImageLayer* combined = back.find("");
  ASSERT_NE(combined, nullptr);
  ASSERT_EQ(combined->rgb.size(), image.layers[0].rgb.size());
  for (size_t i = 0; i < combined->rgb.size(); ++i) {
    const float expected = image.layers[0].rgb[i];
    // Half has an 11-bit significand: relative error at most 2^-11 for normal values.
    EXPECT_NEAR(combined->rgb[i], expected, std::max(std::abs(expected) * 4.9e-4f, 1e-6f))
        << "value " << i;
  }
}

TEST_F(ExrIoTest, FloatRoundTripIsExact) {
  FrameImage image = random_image(13, 11, {""}, 1e5f);
  image.layers[0].rgb[0] = 1.0f / 3.0f;  // not representable as half
  image.layers[0].rgb[1] = 1e-30f;       // far below the half range
  image.layers[0].rgb[2] = 1e30f;        // far above it
  const std::string file = path("float.exr");
  write_exr(file, image, /*full_float=*/true);

  Imf::InputFile raw(file.c_str());
  ASSERT_NE(raw.header().channels().findChannel("B"), nullptr);
  EXPECT_EQ(raw.header().channels().findChannel("B")->type, Imf::FLOAT);

  const FrameImage back = read_exr(file);
  ASSERT_NE(back.find(""), nullptr);
  EXPECT_EQ(back.find("")->rgb, image.layers[0].rgb);
}

TEST_F(ExrIoTest, HalfClampsValuesBeyondTheHalfRange) {
  FrameImage image = random_image(2, 1, {""});
  image.layers[0].rgb[0] = 1e6f;
  image.layers[0].rgb[1] = -1e6f;
  image.layers[0].rgb[2] = 65504.0f;
  const std::string file = path("clamped.exr");
  write_exr(file, image, /*full_float=*/false);
  const FrameImage read = read_exr(file);
  const std::vector<float>& back = read.find("")->rgb;
  EXPECT_EQ(back[0], 65504.0f);
  EXPECT_EQ(back[1], -65504.0f);
  EXPECT_EQ(back[2], 65504.0f);
}

TEST_F(ExrIoTest, LayersAndAttributesArePreserved) {
  FrameImage image = random_image(5, 4, {"", "direct", "indirect.caustic"});
  image.attributes = {{"pmrender/scene", "cornell-box"}, {"pmrender/frame", "7"}};
  const std::string file = path("layers.exr");
  write_exr(file, image, /*full_float=*/true);

  Imf::InputFile raw(file.c_str());
  std::vector<std::string> channel_names;
  for (auto it = raw.header().channels().begin(); it != raw.header().channels().end(); ++it) {
    channel_names.push_back(it.name());
  }
  EXPECT_EQ(channel_names,
            (std::vector<std::string>{"B", "G", "R", "direct.B", "direct.G", "direct.R",
                                      "indirect.caustic.B", "indirect.caustic.G",
                                      "indirect.caustic.R"}));

  const FrameImage back = read_exr(file);
  ASSERT_EQ(back.layers.size(), 3u);
  EXPECT_EQ(back.layers[0].name, "");  // the combined layer comes first
  for (const ImageLayer& layer : image.layers) {
    const ImageLayer* read = back.find(layer.name);
    ASSERT_NE(read, nullptr) << "layer '" << layer.name << "'";
    EXPECT_EQ(read->rgb, layer.rgb) << "layer '" << layer.name << "'";
  }
  const std::map<std::string, std::string> attributes(back.attributes.begin(),
                                                      back.attributes.end());
  ASSERT_EQ(attributes.count("pmrender/scene"), 1u);
  EXPECT_EQ(attributes.at("pmrender/scene"), "cornell-box");
  ASSERT_EQ(attributes.count("pmrender/frame"), 1u);
  EXPECT_EQ(attributes.at("pmrender/frame"), "7");
}

TEST_F(ExrIoTest, NanIsRefusedAndNothingIsWritten) {
  FrameImage image = random_image(4, 4, {""});
  image.layers[0].rgb[17] = std::numeric_limits<float>::quiet_NaN();
  const std::string file = path("nan.exr");
  try {
    write_exr(file, image, false);
    FAIL() << "NaN was written";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find("NaN/Inf"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(file));
  EXPECT_TRUE(entries().empty());
}

TEST_F(ExrIoTest, InfInAnotherLayerIsRefusedAndAnExistingTargetIsKept) {
  const std::string file = path("inf.exr");
  const FrameImage good = random_image(4, 4, {"", "direct"});
  write_exr(file, good, true);
  FrameImage bad = random_image(4, 4, {"", "direct"}, 4.0f, 2);
  bad.layers[1].rgb[5] = std::numeric_limits<float>::infinity();
  EXPECT_THROW(write_exr(file, bad, true), DeviceError);
  EXPECT_EQ(read_exr(file).find("")->rgb, good.layers[0].rgb);
  EXPECT_EQ(entries(), std::vector<std::string>{"inf.exr"});
}

TEST_F(ExrIoTest, SuccessLeavesOnlyTheTarget) {
  write_exr(path("only.exr"), random_image(8, 8, {"", "direct"}), false);
  EXPECT_EQ(entries(), std::vector<std::string>{"only.exr"});
}

TEST_F(ExrIoTest, MissingFoldersAreCreated) {
  const std::string file = path("a/b/c/frame_0001.exr");
  write_exr(file, random_image(3, 3, {""}), false);
  EXPECT_TRUE(fs::is_regular_file(file));
  EXPECT_EQ(entries(), (std::vector<std::string>{"a", "a/b", "a/b/c", "a/b/c/frame_0001.exr"}));
}

TEST_F(ExrIoTest, ExistingTargetIsReplacedByRename) {
  const std::string file = path("frame.exr");
  const FrameImage first = random_image(6, 5, {""}, 4.0f, 1);
  const FrameImage second = random_image(6, 5, {""}, 4.0f, 2);
  write_exr(file, first, true);
  // A hard link keeps the old file reachable: if the writer overwrote the target in place, the
  // link would show the new pixels too; after a rename it still holds the old ones.
  const std::string old_link = path("old_link.exr");
  fs::create_hard_link(file, old_link);
  write_exr(file, second, true);

  EXPECT_EQ(read_exr(file).find("")->rgb, second.layers[0].rgb);
  EXPECT_EQ(read_exr(old_link).find("")->rgb, first.layers[0].rgb);
  EXPECT_EQ(entries(), (std::vector<std::string>{"frame.exr", "old_link.exr"}));
}

TEST_F(ExrIoTest, TargetUnderARegularFileIsADeviceErrorNamingThePath) {
  write_bytes(folder_ / "plain_file", {'x'});
  const std::string file = path("plain_file/frame.exr");
  try {
    write_exr(file, random_image(2, 2, {""}), false);
    FAIL() << "writing under a regular file succeeded";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"plain_file"});
}

TEST_F(ExrIoTest, TargetThatIsAFolderFailsAndLeavesNoTemporary) {
  fs::create_directory(folder_ / "taken.exr");
  const std::string file = path("taken.exr");
  try {
    write_exr(file, random_image(2, 2, {""}), false);
    FAIL() << "writing onto a folder succeeded";
  } catch (const DeviceError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
  EXPECT_EQ(entries(), std::vector<std::string>{"taken.exr"});
}

TEST_F(ExrIoTest, MalformedImageIsRefusedBeforeTouchingTheDisk) {
  FrameImage image = random_image(4, 4, {""});
  image.layers[0].rgb.pop_back();
  EXPECT_THROW(write_exr(path("sub/short.exr"), image, false), DeviceError);
  FrameImage duplicated = random_image(4, 4, {"direct", "direct"});
  EXPECT_THROW(write_exr(path("sub/twice.exr"), duplicated, false), DeviceError);
  EXPECT_TRUE(entries().empty());
}

TEST_F(ExrIoTest, ReadingAMissingFileIsAnInputErrorNamingIt) {
  const std::string file = path("does_not_exist.exr");
  try {
    read_exr(file);
    FAIL() << "reading a missing file succeeded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
}

TEST_F(ExrIoTest, ReadingANonExrFileIsAnInputErrorNamingIt) {
  const std::string file = path("notes.exr");
  const std::string text = "this is not an OpenEXR file, just some text\n";
  write_bytes(file, std::vector<char>(text.begin(), text.end()));
  try {
    read_exr(file);
    FAIL() << "reading a text file succeeded";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
  }
}

TEST_F(ExrIoTest, AnAttributeDeclaringMoreBytesThanTheFileIsRefusedBeforeAllocating) {
  // A real file whose string attribute then claims 2 GB: OpenEXR would allocate that much.
  FrameImage image = random_image(4, 3, {""}, 1.0f);
  image.attributes = {{"pmrender/note", "abcdefgh"}};
  write_exr(path("a.exr"), image, false);
  std::vector<char> bytes = read_bytes(path("a.exr"));
  const std::string marker = std::string("pmrender/note") + '\0' + "string" + '\0';
  const auto at = std::search(bytes.begin(), bytes.end(), marker.begin(), marker.end());
  ASSERT_NE(at, bytes.end());
  const int32_t huge = 2000000000;
  std::memcpy(&*(at + std::ptrdiff_t(marker.size())), &huge, 4);
  write_bytes(path("a.exr"), bytes);
  try {
    read_exr(path("a.exr"));
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("header attribute 'pmrender/note' declares 2000000000 bytes, more than the file holds"),
              std::string::npos) << e.what();
  }
  EXPECT_FALSE(exr_is_complete(path("a.exr")));
}

TEST_F(ExrIoTest, AnImageLargerThanAnyRenderIsRefused) {
  // Written with OpenEXR directly: a 20000 x 1 data window.
  Imf::Header header(20000, 1);
  header.channels().insert("R", Imf::Channel(Imf::HALF));
  header.channels().insert("G", Imf::Channel(Imf::HALF));
  header.channels().insert("B", Imf::Channel(Imf::HALF));
  std::vector<half> row(20000, half(0.5f));
  Imf::FrameBuffer frame_buffer;
  for (const char* c : {"R", "G", "B"})
    frame_buffer.insert(c, Imf::Slice(Imf::HALF, reinterpret_cast<char*>(row.data()), sizeof(half), 0));
  {
    Imf::OutputFile file(path("wide.exr").c_str(), header);
    file.setFrameBuffer(frame_buffer);
    file.writePixels(1);
  }
  try {
    read_exr(path("wide.exr"));
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("the data window is 20000x1, not within 1x1 to 16384x16384"), std::string::npos) << e.what();
  }
}

TEST_F(ExrIoTest, DecodingBuffersBeyond256MiBAreRefused) {
  // 16384 pixels wide with 1200 float channels, DWAB (256 lines at once): OpenEXR would allocate
  // 16384 x 1200 x 4 x 256 bytes (19 GiB) before reading a pixel.
  Imf::Header header(16384, 1);
  header.compression() = Imf::DWAB_COMPRESSION;
  for (int c = 0; c < 1200; ++c) header.channels().insert("c" + std::to_string(c), Imf::Channel(Imf::FLOAT));
  header.channels().insert("R", Imf::Channel(Imf::FLOAT));
  {
    // Only the header is needed; writing no pixels leaves the file incomplete, which is fine here.
    Imf::OutputFile file(path("many.exr").c_str(), header);
  }
  try {
    read_exr(path("many.exr"));
    FAIL() << "read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("channels make decoding buffers of "), std::string::npos) << e.what();
  }
}

TEST_F(ExrIoTest, LayerMissingBlueIsAnInputErrorNamingTheFile) {
  // Written with OpenEXR directly, since write_exr always writes all three channels.
  const std::string file = path("no_blue.exr");
  const int width = 2, height = 2;
  std::vector<float> plane(width * height, 0.5f);
  Imf::Header header(width, height);
  Imf::FrameBuffer frame_buffer;
  for (const char* name : {"R", "G", "direct.R", "direct.G", "direct.B"}) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    frame_buffer.insert(name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(plane.data()),
                                         sizeof(float), sizeof(float) * width));
  }
  {
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame_buffer);
    out.writePixels(height);
  }
  try {
    read_exr(file);
    FAIL() << "a layer without B was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("no B channel"), std::string::npos) << e.what();
  }
}

TEST_F(ExrIoTest, DataWindowAwayFromTheOriginIsRead) {
  const std::string file = path("offset.exr");
  const Imath::Box2i window(Imath::V2i(10, 20), Imath::V2i(13, 22));  // 4 x 3
  Imf::Header header(window, window);
  std::vector<float> red(12), zero(12, 0.0f);
  for (size_t i = 0; i < red.size(); ++i) red[i] = float(i);
  Imf::FrameBuffer frame_buffer;
  for (const char* name : {"R", "G", "B"}) {
    header.channels().insert(name, Imf::Channel(Imf::FLOAT));
    float* data = std::string(name) == "R" ? red.data() : zero.data();
    frame_buffer.insert(name, Imf::Slice::Make(Imf::FLOAT, data, window));
  }
  {
    Imf::OutputFile out(file.c_str(), header);
    out.setFrameBuffer(frame_buffer);
    out.writePixels(3);
  }
  const FrameImage back = read_exr(file);
  ASSERT_EQ(back.width, 4);
  ASSERT_EQ(back.height, 3);
  for (size_t i = 0; i < red.size(); ++i) EXPECT_EQ(back.find("")->rgb[i * 3], red[i]);
}

TEST_F(ExrIoTest, IsCompleteForAWrittenFileAndNotForATruncatedCopy) {
  // Random full-float data barely compresses, so the file has many chunks and half of it
  // really lacks the later scanlines.
  const std::string file = path("whole.exr");
  write_exr(file, random_image(128, 128, {""}, 1.0f), true);
  EXPECT_TRUE(exr_is_complete(file));

  std::vector<char> bytes = read_bytes(file);
  ASSERT_GT(bytes.size(), 100000u);
  bytes.resize(bytes.size() / 2);
  const std::string truncated = path("truncated.exr");
  write_bytes(truncated, bytes);
  EXPECT_FALSE(exr_is_complete(truncated));
  EXPECT_THROW(read_exr(truncated), InputError);

  bytes.resize(20);  // not even a whole header
  write_bytes(truncated, bytes);
  EXPECT_FALSE(exr_is_complete(truncated));
}

TEST_F(ExrIoTest, IsCompleteIsFalseForMissingAndNonExrFiles) {
  EXPECT_FALSE(exr_is_complete(path("missing.exr")));
  write_bytes(folder_ / "text.exr", {'h', 'e', 'l', 'l', 'o'});
  EXPECT_FALSE(exr_is_complete(path("text.exr")));
}

TEST_F(ExrIoTest, CheckTellsMissingTruncatedAndUnreadableApart) {
  const std::string file = path("whole.exr");
  write_exr(file, random_image(128, 96, {""}, 1.0f), true);
  ExrFileCheck whole = check_exr_file(file);
  EXPECT_EQ(whole.state, ExrFileState::complete);
  EXPECT_EQ(whole.width, 128);
  EXPECT_EQ(whole.height, 96);
  EXPECT_TRUE(whole.problem.empty());

  EXPECT_EQ(check_exr_file(path("missing.exr")).state, ExrFileState::missing);

  std::vector<char> bytes = read_bytes(file);
  const std::string cut = path("cut.exr");
  for (size_t keep : {bytes.size() / 2, size_t(20), size_t(2)}) {
    write_bytes(cut, std::vector<char>(bytes.begin(), bytes.begin() + std::ptrdiff_t(keep)));
    const ExrFileCheck check = check_exr_file(cut);
    EXPECT_EQ(check.state, ExrFileState::truncated) << keep << " bytes";
    EXPECT_FALSE(check.problem.empty());
  }
  write_bytes(cut, {});
  EXPECT_EQ(check_exr_file(cut).state, ExrFileState::truncated);
  EXPECT_EQ(check_exr_file(cut).problem, "empty file");

  write_bytes(folder_ / "text.exr", {'h', 'e', 'l', 'l', 'o'});
  EXPECT_EQ(check_exr_file(path("text.exr")).state, ExrFileState::unreadable);
  EXPECT_EQ(check_exr_file(path("text.exr")).problem, "not an OpenEXR file");
  EXPECT_EQ(check_exr_file(folder_.string()).state, ExrFileState::unreadable);
}

}  // namespace
}  // namespace pm
