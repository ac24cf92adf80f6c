// Start-up as a user meets it, on the OpenCL backend in separate pmrender processes: `render -v`
// and `bench` report each start-up step (the driver's start beside the scene load included) and
// the program cache's use, a second process loads the program from the cache, two processes
// racing to fill an empty cache leave one whole entry, an unwritable cache folder renders with
// one warning, and a bad PMRENDER_PROGRAM_CACHE is refused.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "render/exr_io.h"
#include "support/pmrender_process.h"
#include "support/same_image.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

const char* const kTinyRender = "render --backend opencl --resolution 8x8 --photons 500 ";

class StartupCli : public test::PmrenderProcessTest {
 protected:
  void SetUp() override {
    PmrenderProcessTest::SetUp();
    cache_ = dir_ / "cache";
    use_cache(cache_.string());
  }
  void TearDown() override {
    // Back to the test binary's own cache folder (support/test_program_cache.cpp).
    if (saved_) setenv("PMRENDER_CACHE_DIR", saved_->c_str(), 1);
    PmrenderProcessTest::TearDown();
  }
  void use_cache(const std::string& folder) {
    if (!saved_)
      if (const char* old = std::getenv("PMRENDER_CACHE_DIR")) saved_ = old;
    setenv("PMRENDER_CACHE_DIR", folder.c_str(), 1);
  }
  std::vector<std::string> cache_files() const {
    std::vector<std::string> names;
    std::error_code ignored;
    for (const fs::directory_entry& e : fs::directory_iterator(cache_, ignored)) names.push_back(e.path().filename());
    return names;
  }

  fs::path cache_;
  std::optional<std::string> saved_;
};

TEST_F(StartupCli, RenderVerboseReportsTheStepsAndTheSecondRunLoadsTheProgram) {
  test::ProcessResult first = pmrender(std::string(kTinyRender) + "-v -o " + (dir_ / "a.exr").string());
  ASSERT_EQ(first.exit_code, 0) << first.out << first.err;
  for (const char* row : {"start-up, step by step", "scene load", "beside it the opencl driver's start",
                          "opencl 0: platforms", "opencl 0: context", "opencl 0: program", "renderer: BVH build",
                          "renderer: scene upload", "to the first frame", "first frame (host wall)"})
    EXPECT_NE(first.out.find(row), std::string::npos) << "no '" << row << "' in\n" << first.out;
  EXPECT_NE(first.out.find("program cache: opencl 0: stored"), std::string::npos) << first.out;
  EXPECT_EQ(cache_files().size(), 1u);

  test::ProcessResult second = pmrender(std::string(kTinyRender) + "-v -o " + (dir_ / "b.exr").string());
  ASSERT_EQ(second.exit_code, 0) << second.out << second.err;
  EXPECT_NE(second.out.find("program cache: opencl 0: loaded"), std::string::npos) << second.out;
  EXPECT_NE(second.out.find("loaded from the program cache"), std::string::npos) << second.out;
  // The same image from the cached program.
  test::expect_same_image(read_exr((dir_ / "a.exr").string()), read_exr((dir_ / "b.exr").string()),
                          "the program from the cache");
}

TEST_F(StartupCli, TwoProcessesRacingToFillTheCacheLeaveOneWholeEntry) {
  fs::create_directories(dir_ / "one");
  fs::create_directories(dir_ / "two");
  const pid_t one = test::start_pmrender(std::string(kTinyRender) + "-q -o " + (dir_ / "one.exr").string(), dir_ / "one");
  const pid_t two = test::start_pmrender(std::string(kTinyRender) + "-q -o " + (dir_ / "two.exr").string(), dir_ / "two");
  const test::ProcessResult r1 = test::wait_pmrender(one, dir_ / "one"), r2 = test::wait_pmrender(two, dir_ / "two");
  EXPECT_EQ(r1.exit_code, 0) << r1.err;
  EXPECT_EQ(r2.exit_code, 0) << r2.err;
  // One entry and no writer's temporary left beside it.
  const std::vector<std::string> files = cache_files();
  ASSERT_EQ(files.size(), 1u);
  EXPECT_EQ(files[0].rfind("opencl-", 0), 0u) << files[0];
  test::ProcessResult third = pmrender(std::string(kTinyRender) + "-v -o " + (dir_ / "three.exr").string());
  ASSERT_EQ(third.exit_code, 0) << third.err;
  EXPECT_NE(third.out.find("program cache: opencl 0: loaded"), std::string::npos) << third.out;
}

TEST_F(StartupCli, AnUnwritableCacheFolderRendersWithOneWarning) {
  const fs::path blocker = dir_ / "not-a-folder";
  { std::ofstream(blocker) << "x"; }
  use_cache((blocker / "cache").string());
  test::ProcessResult r = pmrender(std::string(kTinyRender) + "-o " + (dir_ / "frame.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_TRUE(fs::exists(dir_ / "frame.exr"));
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("pmrender: warning: cannot write the program cache"), std::string::npos) << r.err;
  // -q prints nothing on success, the warning included.
  test::ProcessResult quiet = pmrender(std::string(kTinyRender) + "-q -o " + (dir_ / "quiet.exr").string());
  EXPECT_EQ(quiet.exit_code, 0);
  EXPECT_EQ(quiet.err, "");
}

TEST_F(StartupCli, BenchReportsStartUpInItsTableAndJson) {
  const fs::path json_path = dir_ / "bench.json";
  test::ProcessResult r = pmrender("bench --backend opencl --resolution 8x8 --photons 500 --warmup 1 --repeat 1 --json " +
                                   json_path.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("start-up, step by step"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("start-up is "), std::string::npos) << r.out;
  const nlohmann::json j = nlohmann::json::parse(test::read_text(json_path));
  const nlohmann::json& startup = j.at("startup");
  EXPECT_GT(startup.at("to_first_frame_ms").get<double>(), 0.0);
  EXPECT_GT(startup.at("first_frame_wall_ms").get<double>(), 0.0);
  bool program = false, bvh = false;
  for (const nlohmann::json& step : startup.at("steps")) {
    program |= step.at("who") == "opencl 0" && step.at("step") == "program";
    bvh |= step.at("who") == "renderer" && step.at("step") == "BVH build";
    EXPECT_GE(step.at("ms").get<double>(), 0.0);
  }
  EXPECT_TRUE(program && bvh) << startup.dump(2);
  EXPECT_EQ(startup.at("program_cache").at(0), "opencl 0: stored");
}

TEST_F(StartupCli, ABadCacheSwitchIsRefusedInOneLine) {
  setenv("PMRENDER_PROGRAM_CACHE", "sometimes", 1);
  test::ProcessResult r = pmrender(std::string(kTinyRender) + "-o " + (dir_ / "frame.exr").string());
  unsetenv("PMRENDER_PROGRAM_CACHE");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("PMRENDER_PROGRAM_CACHE"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "frame.exr"));
}

}  // namespace
}  // namespace pm
