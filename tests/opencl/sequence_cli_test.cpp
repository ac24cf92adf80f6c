// `pmrender render` over sequences on the OpenCL backend, as a user runs it: frame selections
// (bad ones exit 2 and write nothing), chunked runs writing the same pixels as one run, failed
// frames named while the others render, --resume after a SIGKILL rendering only the missing
// frames, stale temporaries removed, and progress drawn on a terminal only.
#include <fcntl.h>
#include <gtest/gtest.h>
#include <pty.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include "render/exr_io.h"
#include "support/paths.h"
#include "support/pmrender_process.h"
#include "support/same_image.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

std::string data(const std::string& name) { return test::test_data_dir() + "/animation/" + name; }

using test::expect_same_image;

using Process = test::ProcessResult;
using test::read_text;

class SequenceCli : public test::PmrenderProcessTest {
 protected:
  void SetUp() override {
    PmrenderProcessTest::SetUp();
    fs::create_directories(dir_ / "out");
  }

  std::string out(const std::string& pattern) { return (dir_ / "out" / pattern).string(); }
  std::set<std::string> files() {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_ / "out")) names.insert(e.path().filename().string());
    return names;
  }
  void expect_usage_error(const std::string& args, const std::string& expected) {
    const Process r = pmrender(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_TRUE(files().empty()) << args;
  }

};

const char kSmall[] = " --backend opencl --resolution 40x30 --photons 20000";

TEST_F(SequenceCli, BadFrameSelectionsExitWith2AndWriteNothing) {
  const std::string scene = data("moving_room.json") + kSmall + " -o " + out("f_####.exr");
  expect_usage_error("render " + scene + " --frames 5-2", "--frames: '5-2': range end is before its start");
  expect_usage_error("render " + scene + " --frames 20-24", "--frames: '20-24': outside the scene's frames 0-23");
  expect_usage_error("render " + scene + " --frames 1,,2", "--frames:");
  expect_usage_error("render " + scene + " --frames x", "--frames: 'x'");
  expect_usage_error("render " + scene + " --frame 24", "--frame: 24 is outside the scene's frames 0-23");
  expect_usage_error("render " + scene + " --frame 1 --frames 2", "--frame and --frames");
  expect_usage_error("render " + data("moving_room.json") + kSmall + " --frames 0-1 -o " + out("single.exr"),
                     "has no # for the frame number, but 2 frames are selected");
  const Process r = pmrender("render " + scene + " --photon-sequence sobol");  // CLI11's usage message
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--photon-sequence"), std::string::npos) << r.err;
  EXPECT_TRUE(files().empty());
  expect_usage_error("render " + data("missing.gltf") + " -o " + out("f_#.exr"), "missing.gltf: cannot open");
}

TEST_F(SequenceCli, StillScenesTakeAnyFrameAndSequencesDefaultToAllTheirFrames) {
  Process r = pmrender(std::string("render") + kSmall + " --frames 3,7 -o " + out("cb_####.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files(), (std::set<std::string>{"cb_0003.exr", "cb_0007.exr"}));
  EXPECT_NE(r.out.find("rendered 2 of 2 frames"), std::string::npos) << r.out;
  fs::remove_all(dir_ / "out");
  fs::create_directories(dir_ / "out");
  r = pmrender("render " + data("twin.json") + " --backend opencl --photons 5000 -o " + out("t_##.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files().size(), 25u);  // frames 0-24: the keys end at 1 s, 24 frames per second
  EXPECT_NE(r.out.find("rendered 25 of 25 frames"), std::string::npos) << r.out;
  const FrameImage f7 = read_exr(out("t_07.exr"));
  bool frame_attribute = false;
  for (const auto& [key, value] : f7.attributes) frame_attribute |= key == "pmrender/frame" && value == "7";
  EXPECT_TRUE(frame_attribute);
}

TEST_F(SequenceCli, ChunkedRunsWriteTheSamePixelsAsOneRun) {
  const std::string scene = "render " + data("moving_room.json") + kSmall + " --float";
  ASSERT_EQ(pmrender(scene + " --frames 8-16 -o " + out("one_####.exr")).exit_code, 0);
  ASSERT_EQ(pmrender(scene + " --frames 8-10 -o " + out("chunk_####.exr")).exit_code, 0);
  ASSERT_EQ(pmrender(scene + " --frames 14-16,11-13 -o " + out("chunk_####.exr")).exit_code, 0);
  for (int f = 8; f <= 16; ++f) {
    char one[32], chunk[32];
    std::snprintf(one, sizeof(one), "one_%04d.exr", f);
    std::snprintf(chunk, sizeof(chunk), "chunk_%04d.exr", f);
    const FrameImage a = read_exr(out(one)), b = read_exr(out(chunk));
    expect_same_image(a, b, "frame " + std::to_string(f));
  }
}

TEST_F(SequenceCli, FailedFramesAreNamedAndTheOthersStillRender) {
  // A target that cannot be written is refused before rendering (output_checks_test.cpp), so
  // frame 2 is made to fail in its write instead: its temporary, ".f_0002.exr.tmp-<pid>-2" (the
  // third file this process writes), is taken by a folder made as soon as the pid is known, long
  // before pmrender has opened its device.
  const pid_t pid = test::start_pmrender(
      "render " + data("moving_room.json") + kSmall + " --frames 0-4 -o " + out("f_####.exr"), dir_);
  ASSERT_GT(pid, 0);
  fs::create_directories(dir_ / "out" / (".f_0002.exr.tmp-" + std::to_string(pid) + "-2"));
  const test::ProcessResult r = test::wait_pmrender(pid, dir_);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("pmrender: frame 2: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("1 of 5 frames failed: 2"), std::string::npos) << r.err;
  for (int f : {0, 1, 3, 4}) EXPECT_TRUE(exr_is_complete(out("f_000" + std::to_string(f) + ".exr"))) << f;
  EXPECT_EQ(test::written_frames(r.out), (std::set<int>{0, 1, 3, 4}));
  for (const std::string& name : files())  // the failed frame's claim too is released
    EXPECT_EQ(name.find(".claim"), std::string::npos) << "left behind: " << name;
}

TEST_F(SequenceCli, ResumeAfterAKilledRunRendersOnlyTheMissingFrames) {
  // The done-when sequence: 24 frames whose camera and lamp both move, killed part-way through.
  const std::string pattern = out("f_####.exr");
  const std::string binary = test::pmrender_binary();
  const std::string scene = data("moving_room.json");
  const pid_t pid = fork();
  ASSERT_GE(pid, 0);
  if (pid == 0) {
    const int null_in = open("/dev/null", O_RDONLY), null_out = open("/dev/null", O_WRONLY);
    dup2(null_in, 0);
    dup2(null_out, 1);
    dup2(null_out, 2);
    execl(binary.c_str(), binary.c_str(), "render", scene.c_str(), "--backend", "opencl", "--resolution", "64x48",
          "--photons", "60000", "--control-paths", "0", "--frames", "0-23", "-o", pattern.c_str(), (char*)nullptr);
    _exit(127);
  }
  auto complete_frames = [&] {
    std::set<int> frames;
    for (int f = 0; f < 24; ++f) {
      char name[32];
      std::snprintf(name, sizeof(name), "f_%04d.exr", f);
      if (fs::exists(dir_ / "out" / name)) frames.insert(f);
    }
    return frames;
  };
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (complete_frames().size() < 3 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_EQ(kill(pid, SIGKILL), 0);
  int status = 0;
  waitpid(pid, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "pmrender finished before it could be killed";
  const std::set<int> before = complete_frames();
  ASSERT_GE(before.size(), 3u);
  ASSERT_LT(before.size(), 24u) << "the whole sequence was written before the kill";
  for (int f : before) {
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    EXPECT_TRUE(exr_is_complete(out(name))) << name << ": a target file is never partial";
  }
  // A partial file (as a copy interrupted by hand would leave) is not complete, so it renders again.
  const int truncated = *before.begin();
  char truncated_name[32];
  std::snprintf(truncated_name, sizeof(truncated_name), "f_%04d.exr", truncated);
  fs::resize_file(dir_ / "out" / truncated_name, fs::file_size(dir_ / "out" / truncated_name) / 2);
  std::map<int, fs::file_time_type> mtimes;
  for (int f : before) {
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    mtimes[f] = fs::last_write_time(dir_ / "out" / name);
  }

  const Process r = pmrender("render " + scene + " --backend opencl --resolution 64x48 --photons 60000 --control-paths 0 "
                             "--frames 0-23 --resume -v -o " + pattern);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::set<int> expected;
  for (int f = 0; f < 24; ++f)
    if (!before.count(f) || f == truncated) expected.insert(f);
  EXPECT_EQ(test::written_frames(r.out), expected) << r.out;
  for (int f : before) {
    if (f == truncated) continue;
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    EXPECT_NE(r.out.find(std::string("skipped ") + out(name) + " (complete)"), std::string::npos) << r.out;
    EXPECT_EQ(fs::last_write_time(dir_ / "out" / name), mtimes[f]) << name << " was rewritten";
  }
  for (int f = 0; f < 24; ++f) {
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    EXPECT_TRUE(exr_is_complete(out(name))) << name;
  }
  for (const std::string& name : files()) EXPECT_EQ(name.find(".tmp-"), std::string::npos) << "left behind: " << name;
  EXPECT_EQ(files().size(), 24u);
}

TEST_F(SequenceCli, StaleTemporariesOfDeadProcessesAreRemoved) {
  // What write_exr leaves when killed mid-write: ".<name>.tmp-<pid>-<n>" of a process that is gone.
  pid_t dead = fork();
  if (dead == 0) _exit(0);
  waitpid(dead, nullptr, 0);
  const std::string stale = ".f_0001.exr.tmp-" + std::to_string(dead) + "-0";
  const std::string live = ".f_0001.exr.tmp-" + std::to_string(getpid()) + "-0";  // ours: alive
  std::ofstream(dir_ / "out" / stale) << "partial";
  std::ofstream(dir_ / "out" / live) << "partial";
  const Process r = pmrender("render " + data("moving_room.json") + kSmall + " --frames 1 -v -o " + out("f_####.exr"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(files(), (std::set<std::string>{"f_0001.exr", live}));
  EXPECT_NE(r.out.find("removed stale temporary"), std::string::npos) << r.out;
}

// Runs pmrender with its standard error on a pseudo-terminal and returns what it printed there.
std::string run_on_terminal(const std::vector<std::string>& args) {
  int master = -1;
  const pid_t pid = forkpty(&master, nullptr, nullptr, nullptr);
  if (pid == 0) {
    const int null_fd = open("/dev/null", O_RDWR);
    dup2(null_fd, 0);
    dup2(null_fd, 1);  // only standard error stays on the terminal
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    execv(argv[0], argv.data());
    _exit(127);
  }
  std::string text;
  char buffer[4096];
  for (;;) {
    const ssize_t n = read(master, buffer, sizeof(buffer));
    if (n <= 0) break;  // EIO once the child has closed the terminal
    text.append(buffer, size_t(n));
  }
  waitpid(pid, nullptr, 0);
  close(master);
  return text;
}

TEST_F(SequenceCli, ProgressGoesToATerminalOnlyAndQuietSilencesIt) {
  const std::vector<std::string> base = {test::pmrender_binary(), "render", data("moving_room.json"), "--backend",
                                         "opencl", "--resolution", "40x30", "--photons", "20000", "--frames", "0-3",
                                         "-o", out("f_####.exr")};
  const std::string terminal = run_on_terminal(base);
  EXPECT_NE(terminal.find("4/4 (100%)"), std::string::npos) << terminal;
  EXPECT_NE(terminal.find("/frame  ETA "), std::string::npos) << terminal;
  std::vector<std::string> quiet = base;
  quiet.push_back("--quiet");
  EXPECT_EQ(run_on_terminal(quiet), "");
  const Process piped = pmrender("render " + data("moving_room.json") + kSmall + " --frames 12-15 -o " + out("f_####.exr"));
  ASSERT_EQ(piped.exit_code, 0);
  EXPECT_EQ(piped.err.find("ETA"), std::string::npos) << piped.err;
  EXPECT_NE(piped.out.find("rendered 4 of 4 frames"), std::string::npos) << piped.out;
  EXPECT_NE(piped.out.find("photons reused in 3"), std::string::npos) << piped.out;  // 13-15 share 12's lamp
}

}  // namespace
}  // namespace pm
