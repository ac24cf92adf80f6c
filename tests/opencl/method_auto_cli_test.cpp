// `pmrender render --method auto` end to end on PoCL: the race's choice is printed and written
// into every frame's header, the first frame goes on from the race and stops at the target, and
// without a budget (or without the error control) auto is refused before any rendering.
#include <gtest/gtest.h>

#include <filesystem>
#include <map>
#include <string>

#include "render/exr_io.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

class MethodAutoCli : public test::PmrenderProcessTest {};

std::map<std::string, std::string> header(const fs::path& path) {
  std::map<std::string, std::string> values;
  for (const auto& [key, value] : read_exr(path.string()).attributes) values[key] = value;
  return values;
}

TEST_F(MethodAutoCli, TheChoiceIsPrintedAndInEveryFramesHeader) {
  const test::ProcessResult r = pmrender("render --backend opencl --method auto --target-error 0.5 --resolution 16x16 "
                                         "--photons 4096 --frames 0-1 -o " + (dir_ / "auto_#.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("method auto: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("raced on frame 0"), std::string::npos) << r.out;
  for (const char* frame : {"auto_0.exr", "auto_1.exr"}) {
    SCOPED_TRACE(frame);
    std::map<std::string, std::string> h = header(dir_ / frame);
    const std::string choice = h["pmrender/method_choice"];
    EXPECT_TRUE(choice == "photon" || choice == "photon --final-gather 16" || choice == "path" || choice == "radiosity" ||
                choice == "radiosity --final-gather 16")
        << choice;
    // Every candidate appears in the race's line, and the frame's settings are the winner's.
    for (const char* label :
         {"photon: ", "photon --final-gather 16: ", "path: ", "radiosity: ", "radiosity --final-gather 16: "})
      EXPECT_NE(h["pmrender/method_race"].find(label), std::string::npos) << h["pmrender/method_race"];
    EXPECT_NE(h["pmrender/settings"].find("method=" + choice.substr(0, choice.find(' ')) + " "), std::string::npos)
        << h["pmrender/settings"];
    ASSERT_FALSE(h["pmrender/error_estimate"].empty());
    EXPECT_LE(std::stod(h["pmrender/error_estimate"]), 0.5);
  }
}

TEST_F(MethodAutoCli, WithoutABudgetOrControlItIsRefusedBeforeRendering) {
  const test::ProcessResult none = pmrender("render --backend opencl --method auto -o " + (dir_ / "x.exr").string());
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_NE(none.err.find("--method: auto races the methods under a budget"), std::string::npos) << none.err;
  const test::ProcessResult blind = pmrender("render --backend opencl --method auto --time 1 --control-paths 0 -o " +
                                             (dir_ / "x.exr").string());
  EXPECT_EQ(blind.exit_code, 2);
  EXPECT_NE(blind.err.find("--control-paths: 0 leaves --method auto nothing"), std::string::npos) << blind.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.exr"));
}

}  // namespace
}  // namespace pm
