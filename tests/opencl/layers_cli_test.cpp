// `pmrender render --layers` as a user meets it on the OpenCL backend: the channels and header
// attributes of the written file (read back with the project's own reader), half and float files,
// a file without --layers holding only the four colour layers, the one-line refusal of an unknown
// layer before anything is loaded, the commands that read frames (compare, frames check,
// --resume over a checkpoint, --preview) working on files with layers, and farm scripts passing
// the option on.
#include <gtest/gtest.h>

#include <signal.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <map>
#include <string>
#include <thread>
#include <vector>

#include "render/exr_io.h"
#include "support/paths.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
using test::ProcessResult;

const char kSmall[] = " --backend opencl --resolution 24x18 --photons 3000";

std::map<std::string, std::string> attributes_of(const FrameImage& image) {
  return std::map<std::string, std::string>(image.attributes.begin(), image.attributes.end());
}

// Every channel the file holds, as read_exr groups them back.
std::vector<std::string> channels_of(const FrameImage& image) {
  std::vector<std::string> names;
  for (const ImageLayer& layer : image.layers)
    for (const char* c : {"R", "G", "B"}) names.push_back(layer.name.empty() ? c : layer.name + "." + c);
  for (const DataLayer& layer : image.data_layers)
    for (size_t c = 0; c < layer.channels.size(); ++c) names.push_back(layer.channel_name(c));
  std::sort(names.begin(), names.end());
  return names;
}

class LayersCli : public test::PmrenderProcessTest {
 protected:
  std::string out(const std::string& name) { return (dir_ / name).string(); }
};

TEST_F(LayersCli, AllLayersGiveTheirChannelsAndHeader) {
  const ProcessResult r = pmrender("render" + std::string(kSmall) + " --layers all -o " + out("a.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const FrameImage image = read_exr(out("a.exr"));
  EXPECT_EQ(channels_of(image),
            (std::vector<std::string>{"B", "G", "N.X", "N.Y", "N.Z", "P.X", "P.Y", "P.Z", "R", "Z", "albedo.B",
                                      "albedo.G", "albedo.R", "caustic.B", "caustic.G", "caustic.R", "direct.B",
                                      "direct.G", "direct.R", "indirect.B", "indirect.G", "indirect.R",
                                      "material_id.X", "object_id.X"}));
  std::map<std::string, std::string> a = attributes_of(image);
  EXPECT_EQ(a["pmrender/layers"],
            "albedo:albedo.R,albedo.G,albedo.B normal:N.X,N.Y,N.Z depth:Z position:P.X,P.Y,P.Z "
            "object_id:object_id.X material_id:material_id.X");
  EXPECT_EQ(a["pmrender/depth_miss"], "65504");  // a half file
  EXPECT_EQ(a["pmrender/object_ids"], "0=floor; 1=ceiling; 2=back wall; 3=green wall; 4=red wall; 5=short block; "
                                      "6=tall block");
  EXPECT_EQ(a["pmrender/material_ids"], "0=white; 1=red; 2=green");
  // Ids are float channels even in a half file, and hold whole numbers of the scene's objects.
  const DataLayer* objects = image.find_data("object_id");
  ASSERT_NE(objects, nullptr);
  EXPECT_TRUE(objects->full_float);
  EXPECT_FALSE(image.find_data("N")->full_float);
  std::vector<bool> seen(7, false);
  for (float id : objects->values) {
    ASSERT_EQ(id, float(int(id)));
    ASSERT_TRUE(id >= -1 && id <= 6) << id;
    if (id >= 0) seen[size_t(id)] = true;
  }
  EXPECT_TRUE(seen[0] && seen[2] && seen[3] && seen[4] && seen[6]);  // the camera sees these at least
}

TEST_F(LayersCli, FloatFilesWriteEveryLayerAsFloatAndTheMissDepthAsIs) {
  ASSERT_EQ(pmrender("render" + std::string(kSmall) + " --float --layers depth,normal -o " + out("f.exr")).exit_code, 0);
  const FrameImage image = read_exr(out("f.exr"));
  ASSERT_NE(image.find_data(""), nullptr);
  EXPECT_TRUE(image.find_data("")->full_float && image.find_data("N")->full_float);
  EXPECT_EQ(image.find("albedo"), nullptr);
  EXPECT_EQ(image.find_data("P"), nullptr);
  EXPECT_EQ(attributes_of(image)["pmrender/layers"], "normal:N.X,N.Y,N.Z depth:Z");
  EXPECT_EQ(attributes_of(image)["pmrender/depth_miss"], "1e+10");
}

TEST_F(LayersCli, WithoutLayersTheFileHoldsTheFourColourLayersOnly) {
  ASSERT_EQ(pmrender("render" + std::string(kSmall) + " -o " + out("plain.exr")).exit_code, 0);
  const FrameImage image = read_exr(out("plain.exr"));
  EXPECT_EQ(channels_of(image), (std::vector<std::string>{"B", "G", "R", "caustic.B", "caustic.G", "caustic.R",
                                                          "direct.B", "direct.G", "direct.R", "indirect.B",
                                                          "indirect.G", "indirect.R"}));
  for (const auto& [name, value] : image.attributes)
    EXPECT_TRUE(name.rfind("pmrender/layers", 0) != 0 && name.find("_ids") == std::string::npos &&
                name != "pmrender/depth_miss")
        << name;
}

TEST_F(LayersCli, AnUnknownLayerIsRefusedInOneLineBeforeAnyWork) {
  // The scene does not exist: the option is checked before it would be loaded.
  for (const std::string value : {"foo", "albedo,foo", "albedo,"}) {
    SCOPED_TRACE(value);
    const ProcessResult r = pmrender("render missing_scene.json --layers '" + value + "' -o " + out("x.exr"));
    EXPECT_EQ(r.exit_code, 2);
    EXPECT_EQ(r.err.rfind("pmrender: --layers: ", 0), 0u) << r.err;
    EXPECT_NE(r.err.find("'" + value + "'"), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(out("x.exr")));
  }
}

TEST_F(LayersCli, CompareFramesCheckAndPreviewReadFilesWithLayers) {
  const std::string args = "render" + std::string(kSmall) + " --layers all --frames 0-1 -o " + out("s_#.exr") +
                           " --preview " + out("s_#.png");
  ASSERT_EQ(pmrender(args).exit_code, 0);
  EXPECT_TRUE(fs::exists(out("s_0.png")) && fs::exists(out("s_1.png")));
  ProcessResult r = pmrender("frames check -o " + out("s_#.exr") + " --frames 0-1 --resolution 24x18");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out, "2 frames: 2 complete\n");
  r = pmrender("compare " + out("s_0.exr") + " " + out("s_1.exr") + " --layer albedo");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;  // a still scene: the same albedo in every frame
  r = pmrender(args + " --resume -v");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("skipped " + out("s_0.exr") + " (complete)"), std::string::npos) << r.out;
}

TEST_F(LayersCli, FarmScriptsPassTheLayersOnAndRefuseUnknownOnes) {
  const std::string farm = "farm slurm --chunk 2 --frames 0-3 -o " + out("f_#.exr") + " --script " + out("job.sh");
  ProcessResult r = pmrender(farm + " --layers albedo,depth");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(test::read_text(out("job.sh")).find(" render --layers albedo,depth "), std::string::npos);
  fs::remove(out("job.sh"));
  r = pmrender(farm + " --layers bogus");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--layers: unknown layer 'bogus'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out("job.sh")));
}

TEST_F(LayersCli, AFrameResumedFromItsCheckpointHasItsLayers) {
  const std::string args = "render --backend opencl --resolution 24x18 --photons 2000 --passes 40 "
                           "--checkpoint-every 2 --layers depth,object_id --float -o " + out("c.exr");
  const pid_t pid = test::start_pmrender(args, dir_);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(60);
  while (!fs::exists(out("c.exr.pmstate")) && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  kill(pid, SIGKILL);
  test::wait_pmrender(pid, dir_);
  ASSERT_TRUE(fs::exists(out("c.exr.pmstate"))) << "no checkpoint was written";
  ASSERT_FALSE(exr_is_complete(out("c.exr"))) << "the frame finished before it could be killed";

  const ProcessResult r = pmrender(args + " --resume");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("continued from its checkpoint"), std::string::npos) << r.out;
  const FrameImage image = read_exr(out("c.exr"));
  ASSERT_NE(image.find_data(""), nullptr);
  ASSERT_NE(image.find_data("object_id"), nullptr);
  EXPECT_EQ(attributes_of(image)["pmrender/layers"], "depth:Z object_id:object_id.X");
  // Inside the box (metres from the camera), or the miss value beside it (a 4:3 frame of a square box).
  size_t inside = 0;
  for (float depth : image.find_data("")->values) {
    EXPECT_TRUE((depth > 0 && depth < 10) || depth == 1e10f) << depth;
    inside += depth < 10;
  }
  EXPECT_GT(inside, image.find_data("")->values.size() / 2);
}

}  // namespace
}  // namespace pm
