// SIGINT and SIGTERM sent to a real pmrender process in the middle of a sequence: the finished
// frames stay and are complete, no temporary, partial file or frame claim remains, the message
// says how far it got, and the exit code is 128 + the signal (130, 143).
#include <csignal>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <thread>

#include "render/exr_io.h"
#include "render/interruption.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

class Interrupt : public test::PmrenderProcessTest {
 protected:
  void interrupt_mid_sequence(int signal_number, int expected_exit_code) {
    const int total = 400;
    const pid_t pid = test::start_pmrender("render --backend opencl --resolution 24x24 --photons 2000 --frames 0-" +
                                               std::to_string(total - 1) + " -o " + (dir_ / "f_###.exr").string(),
                                           dir_);
    ASSERT_GT(pid, 0);
    // Two finished frames: the device is up and the loop is running.
    const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
    while (!fs::exists(dir_ / "f_001.exr") && std::chrono::steady_clock::now() < deadline)
      std::this_thread::sleep_for(std::chrono::milliseconds(5));
    ASSERT_TRUE(fs::exists(dir_ / "f_001.exr"));
    ::kill(pid, signal_number);
    const test::ProcessResult r = test::wait_pmrender(pid, dir_);

    EXPECT_EQ(r.exit_code, expected_exit_code) << r.err;
    std::smatch match;
    ASSERT_TRUE(std::regex_search(r.err, match, std::regex("^pmrender: interrupted after ([0-9]+) of 400 frames\n$")))
        << r.err;
    const int done = std::stoi(match[1].str());
    EXPECT_GE(done, 2);
    EXPECT_LT(done, total);
    int exr_files = 0;
    for (const auto& entry : fs::directory_iterator(dir_)) {
      const std::string name = entry.path().filename().string();
      EXPECT_EQ(name.find(".tmp-"), std::string::npos) << "temporary left: " << name;
      EXPECT_NE(entry.path().extension(), ".claim") << "frame claim left: " << name;
      if (entry.path().extension() != ".exr") continue;
      ++exr_files;
      EXPECT_TRUE(exr_is_complete(entry.path().string())) << name;
    }
    EXPECT_EQ(exr_files, done);
  }
};

TEST_F(Interrupt, SigintStopsBetweenFramesWithCode130) { interrupt_mid_sequence(SIGINT, 130); }
TEST_F(Interrupt, SigtermStopsBetweenFramesWithCode143) { interrupt_mid_sequence(SIGTERM, 143); }

// A stop requested while a frame is being written: the writer throws Interrupted and removes its
// temporary. Run in a child process (death-test style) so the request does not reach other tests;
// "threadsafe" re-executes this binary for the child instead of forking it, so the child inherits
// no GPU driver state (a forked child's exit broke the parent's NVIDIA OpenCL context).
TEST(InterruptedWrite, LeavesNeitherTargetNorTemporary) {
  testing::GTEST_FLAG(death_test_style) = "threadsafe";
  const fs::path dir = test::process_temp_dir() / "interrupted_write";
  fs::remove_all(dir);
  fs::create_directories(dir);
  FrameImage image;
  image.width = 16;
  image.height = 16;
  image.layers.push_back({"", std::vector<float>(16 * 16 * 3, 0.25f)});
  EXPECT_EXIT(
      {
        request_interruption(SIGINT);
        bool interrupted = false;
        try {
          write_exr((dir / "f.exr").string(), image, false);
        } catch (const Interrupted&) {
          interrupted = true;
        }
        std::exit(interrupted && fs::is_empty(dir) ? 0 : 1);
      },
      ::testing::ExitedWithCode(0), "");
  EXPECT_TRUE(fs::is_empty(dir));
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pm
