// `pmrender render --devices` end to end: a sequence's frames shared between two devices are the
// frames one device renders, bit for bit, and both devices take part; a frame's passes shared
// between two devices add up to the one-device frame up to float rounding. On two GPUs of one model
// where the machine has them; elsewhere PoCL stands in, its CPU device listed twice (POCL_DEVICES).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <regex>
#include <sstream>

#include "render/exr_io.h"
#include "support/paths.h"
#include "support/pmrender_process.h"
#include "support/same_image.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

const char kSmall[] = " --backend opencl --resolution 40x30 --photons 20000 --float";

class MultiDeviceCli : public test::PmrenderProcessTest {
 protected:
  void SetUp() override {
    PmrenderProcessTest::SetUp();
    // Two OpenCL devices of one model: two GPUs where the machine has them, else PoCL's CPU device
    // listed twice (PoCL 3 names its CPU driver "pthread", PoCL 5 "cpu").
    if (find_two_alike()) return;
    for (const char* twice : {"pthread pthread", "cpu cpu"}) {
      setenv("POCL_DEVICES", twice, 1);
      if (find_two_alike()) return;
    }
    unsetenv("POCL_DEVICES");
  }
  // The indices of the first two devices `pmrender devices` lists under one name.
  bool find_two_alike() {
    const test::ProcessResult r = pmrender("devices");
    std::istringstream lines(r.out);
    std::map<std::string, std::vector<std::string>> by_name;
    for (std::string line; std::getline(lines, line);) {
      std::smatch m;
      if (!std::regex_search(line, m, std::regex("^opencl +--device ([0-9]+) +(.*)$"))) continue;
      std::vector<std::string>& indices = by_name[m[2]];
      indices.push_back(m[1]);
      if (indices.size() == 2) {
        pair_ = indices;
        return true;
      }
    }
    return false;
  }
  void TearDown() override {
    unsetenv("POCL_DEVICES");
    PmrenderProcessTest::TearDown();
  }
  std::string out(const std::string& name) { return (dir_ / name).string(); }
  std::string scene() const { return test::test_data_dir() + "/animation/moving_room.json"; }

  std::vector<std::string> pair_;  // the indices of two devices of one model
};

TEST_F(MultiDeviceCli, SequenceFramesOnTwoDevicesAreTheFramesOfOne) {
  ASSERT_EQ(pair_.size(), 2u) << "no two OpenCL devices of one model, not even PoCL with POCL_DEVICES";
  const std::string render = "render " + scene() + kSmall + " --frames 0-7";
  const test::ProcessResult one = pmrender(render + " --device " + pair_[0] + " -o " + out("one_####.exr"));
  ASSERT_EQ(one.exit_code, 0) << one.err;
  const test::ProcessResult two = pmrender(render + " --devices " + pair_[0] + "," + pair_[1] + " -o " + out("two_####.exr"));
  ASSERT_EQ(two.exit_code, 0) << two.err;
  EXPECT_EQ(test::written_frames(two.out).size(), 8u) << two.out;
  std::smatch m;
  const std::string& text = two.out;
  ASSERT_TRUE(std::regex_search(text, m, std::regex("frames per device: ([0-9]+), ([0-9]+)"))) << two.out;
  EXPECT_EQ(std::stoi(m[1]) + std::stoi(m[2]), 8);
  EXPECT_GT(std::stoi(m[1]), 0) << two.out;
  EXPECT_GT(std::stoi(m[2]), 0) << two.out;
  for (int f = 0; f < 8; ++f) {
    char a[32], b[32];
    std::snprintf(a, sizeof(a), "one_%04d.exr", f);
    std::snprintf(b, sizeof(b), "two_%04d.exr", f);
    test::expect_same_image(read_exr(out(a)), read_exr(out(b)), "frame " + std::to_string(f));
  }
}

TEST_F(MultiDeviceCli, AFrameWhosePassesTwoDevicesShareIsTheFrameOfOne) {
  ASSERT_EQ(pair_.size(), 2u) << "no two OpenCL devices of one model, not even PoCL with POCL_DEVICES";
  const std::string render = "render " + scene() + kSmall + " --frame 3 --passes 8 --progressive shrink";
  ASSERT_EQ(pmrender(render + " --device " + pair_[0] + " -o " + out("one.exr")).exit_code, 0);
  const test::ProcessResult two = pmrender(render + " --devices " + pair_[0] + "," + pair_[1] + " -o " + out("two.exr"));
  ASSERT_EQ(two.exit_code, 0) << two.err;
  test::expect_same_passes_in_another_order(read_exr(out("one.exr")), read_exr(out("two.exr")));
}

}  // namespace
}  // namespace pm
