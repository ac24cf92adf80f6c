// Frame claims with real pmrender processes on the OpenCL backend: two renders of one pattern at
// once render every frame exactly once between them; a run killed with SIGKILL leaves a stale
// claim that `frames check` names and the next run takes over (and a stale claim beside a
// complete frame is removed, the frame kept); a frame claimed by a live process
// is skipped (exit 0, named by `frames check` as being rendered), or waited for and taken over
// once that process is gone with --wait-for-claimed-frames.
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <thread>

#include "render/exr_io.h"
#include "render/frame_claim.h"
#include "support/paths.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
using test::ProcessResult;

std::string scene_path() { return test::test_data_dir() + "/animation/moving_room.json"; }

// Frames of a few hundred milliseconds on any device (passes until 0.3 s are spent; one pass takes
// about that on PoCL, a few milliseconds on a GPU, where a frame of one pass let the first process
// finish every frame before the second had started), so that processes overlap and a kill lands in
// one; without the error estimate, whose control paths grow with the frame's own time.
const char kFrameOptions[] = " --backend opencl --resolution 48x36 --photons 75000 --time 0.3 --control-paths 0";


class FrameClaimsCli : public test::PmrenderProcessTest {
 protected:
  void SetUp() override {
    PmrenderProcessTest::SetUp();
    for (const char* sub : {"out", "a", "b"}) fs::create_directories(dir_ / sub);
  }
  std::string pattern() const { return (dir_ / "out" / "f_####.exr").string(); }
  std::string frame_path(int f) const {
    char name[32];
    std::snprintf(name, sizeof(name), "f_%04d.exr", f);
    return (dir_ / "out" / name).string();
  }
  std::string render_args(const std::string& frames) const {
    return "render " + scene_path() + kFrameOptions + " --frames " + frames + " -o " + pattern();
  }
  std::set<std::string> claim_files() const {
    std::set<std::string> names;
    for (const auto& e : fs::directory_iterator(dir_ / "out"))
      if (e.path().extension() == ".claim") names.insert(e.path().filename().string());
    return names;
  }
  void expect_all_complete(int first, int last) const {
    for (int f = first; f <= last; ++f) EXPECT_TRUE(exr_is_complete(frame_path(f))) << "frame " << f;
  }
  // A claim on frame f written for pid (a process of this host that is not pmrender).
  void write_claim_for(int f, pid_t pid) {
    ClaimRecord record;
    record.owner = this_process_identity();
    record.owner.pid = long(pid);
    record.owner.start_ticks = process_start_ticks(pid).value_or(0);
    record.started_unix_seconds = long(std::time(nullptr));
    std::ofstream(claim_path_for(frame_path(f))) << claim_text(record);
  }
};

pid_t start_sleeper() {
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sleep", "sleep", "600", static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

TEST_F(FrameClaimsCli, TwoRendersOfOnePatternAtOnceRenderEachFrameOnce) {
  const int last = 15;
  const std::string args = render_args("0-" + std::to_string(last)) + " --resume";
  const pid_t a = test::start_pmrender(args, dir_ / "a");
  const pid_t b = test::start_pmrender(args, dir_ / "b");
  ASSERT_GT(a, 0);
  ASSERT_GT(b, 0);
  const ProcessResult ra = test::wait_pmrender(a, dir_ / "a"), rb = test::wait_pmrender(b, dir_ / "b");
  ASSERT_EQ(ra.exit_code, 0) << ra.err;
  ASSERT_EQ(rb.exit_code, 0) << rb.err;
  const std::set<int> by_a = test::written_frames(ra.out), by_b = test::written_frames(rb.out);
  for (int f : by_a) EXPECT_EQ(by_b.count(f), 0u) << "frame " << f << " was rendered by both\n" << ra.out << rb.out;
  std::set<int> all = by_a;
  all.insert(by_b.begin(), by_b.end());
  EXPECT_EQ(all.size(), size_t(last + 1)) << ra.out << rb.out;
  // Both really ran at once: each rendered some frames and saw the other's claims.
  EXPECT_FALSE(by_a.empty()) << ra.out;
  EXPECT_FALSE(by_b.empty()) << rb.out;
  EXPECT_NE((ra.out + rb.out).find("(being rendered by pid "), std::string::npos) << ra.out << rb.out;
  expect_all_complete(0, last);
  EXPECT_TRUE(claim_files().empty());
  EXPECT_EQ(pmrender("frames check -q -o " + pattern() + " --frames 0-" + std::to_string(last)).exit_code, 0);
}

TEST_F(FrameClaimsCli, WaitingRendersEndOnlyWhenEveryFrameIsComplete) {
  const int last = 11;
  const std::string args = render_args("0-" + std::to_string(last)) + " --resume --wait-for-claimed-frames";
  const pid_t a = test::start_pmrender(args, dir_ / "a");
  const pid_t b = test::start_pmrender(args, dir_ / "b");
  ASSERT_GT(a, 0);
  ASSERT_GT(b, 0);
  // Whichever ends first: every frame is complete at that moment.
  int status = 0;
  pid_t first = 0;
  while (first == 0) {
    for (pid_t p : {a, b})
      if (first == 0 && waitpid(p, &status, WNOHANG) == p) first = p;
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0);
  expect_all_complete(0, last);
  const pid_t second = first == a ? b : a;
  const ProcessResult r = test::wait_pmrender(second, dir_ / (second == a ? "a" : "b"));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::set<int> by_a = test::written_frames(test::read_text(dir_ / "a" / "stdout.txt"));
  const std::set<int> by_b = test::written_frames(test::read_text(dir_ / "b" / "stdout.txt"));
  for (int f : by_a) EXPECT_EQ(by_b.count(f), 0u) << "frame " << f << " was rendered by both";
  EXPECT_EQ(by_a.size() + by_b.size(), size_t(last + 1));
  EXPECT_TRUE(claim_files().empty());
}

TEST_F(FrameClaimsCli, KilledRunLeavesAStaleClaimThatTheNextRunTakesOver) {
  const pid_t killed = test::start_pmrender(render_args("0-7"), dir_ / "a");
  ASSERT_GT(killed, 0);
  // Kill it while it renders frame 2 with frames 0 and 1 done: frame 2 claimed, frame 1's file in
  // place and its claim released (a frame's file is written while the next one renders, so for a
  // moment both are claimed).
  const int claimed = 2;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (!(fs::exists(claim_path_for(frame_path(claimed))) && fs::exists(frame_path(claimed - 1)) &&
           !fs::exists(claim_path_for(frame_path(claimed - 1)))) &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(1));
  ASSERT_EQ(kill(killed, SIGKILL), 0);
  int status = 0;
  waitpid(killed, &status, 0);
  ASSERT_TRUE(WIFSIGNALED(status)) << "pmrender finished before it could be killed";
  ASSERT_EQ(claim_files(), std::set<std::string>{"f_0002.exr.claim"}) << "the frame being rendered keeps its claim";
  EXPECT_FALSE(fs::exists(frame_path(claimed)));
  expect_all_complete(0, 1);

  ProcessResult r = pmrender("frames check -o " + pattern() + " --frames 0-7");
  EXPECT_EQ(r.exit_code, 1);
  const std::string stale_line = "frame " + std::to_string(claimed) + ": " + frame_path(claimed) +
                                 ": stale claim (missing, no such file; pid " + std::to_string(killed) + " on ";
  EXPECT_NE(r.out.find(stale_line), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(" is no longer running)\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(", 1 stale claim"), std::string::npos) << r.out;

  // What a kill between a frame's rename and its claim's removal leaves: a complete frame with a
  // stale claim. --resume keeps the frame and removes the claim.
  fs::copy_file(claim_path_for(frame_path(claimed)), claim_path_for(frame_path(0)));
  r = pmrender(render_args("0-7") + " --resume -v");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(test::written_frames(r.out).count(0), 0u) << r.out;
  EXPECT_NE(r.out.find("removed stale claim " + claim_path_for(frame_path(0)) + ": pid " + std::to_string(killed)),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("took over the stale claim " + claim_path_for(frame_path(claimed)) + ": pid " +
                       std::to_string(killed) + " on "),
            std::string::npos)
      << r.out;
  EXPECT_EQ(test::written_frames(r.out).count(claimed), 1u) << r.out;
  expect_all_complete(0, 7);
  EXPECT_TRUE(claim_files().empty());
}

TEST_F(FrameClaimsCli, FrameClaimedByALiveProcessIsSkippedOrWaitedFor) {
  const pid_t sleeper = start_sleeper();
  ASSERT_GT(sleeper, 0);
  std::this_thread::sleep_for(std::chrono::milliseconds(50));  // it has exec'd: its start time is its own
  write_claim_for(1, sleeper);

  ProcessResult r = pmrender(render_args("0-2"));
  EXPECT_EQ(r.exit_code, 0) << "frames another process renders are not a failure\n" << r.err;
  EXPECT_EQ(test::written_frames(r.out), (std::set<int>{0, 2}));
  EXPECT_NE(r.out.find("skipped " + frame_path(1) + " (being rendered by pid " + std::to_string(sleeper) + " on "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("rendered 2 of 3 frames"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find(", 1 being rendered by other processes\n"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(claim_path_for(frame_path(1)))) << "a live claim is never removed";

  r = pmrender("frames check -o " + pattern() + " --frames 0-2");
  EXPECT_EQ(r.exit_code, 1) << "a frame still being rendered is not complete";
  EXPECT_NE(r.out.find("frame 1: " + frame_path(1) + ": being rendered (missing, no such file; claimed by pid " +
                       std::to_string(sleeper) + " on "),
            std::string::npos)
      << r.out;
  EXPECT_NE(r.out.find("3 frames: 2 complete, 1 being rendered"), std::string::npos) << r.out;

  // Waiting: the claim's process ends without the frame, so the waiting run renders it itself.
  const pid_t waiting = test::start_pmrender(render_args("0-2") + " --resume --wait-for-claimed-frames", dir_ / "b");
  ASSERT_GT(waiting, 0);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(120);
  while (test::read_text(dir_ / "b" / "stdout.txt").find("waiting for") == std::string::npos &&
         std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  std::this_thread::sleep_for(std::chrono::seconds(2));  // a few rounds of looking again
  EXPECT_EQ(waitpid(waiting, nullptr, WNOHANG), 0) << "it does not end while the frame is claimed";
  kill(sleeper, SIGKILL);
  waitpid(sleeper, nullptr, 0);
  r = test::wait_pmrender(waiting, dir_ / "b");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("waiting for 1 frame other processes are rendering: 1\n"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("took over the stale claim " + claim_path_for(frame_path(1)) + ": pid " +
                       std::to_string(sleeper) + " on "),
            std::string::npos)
      << r.out;
  EXPECT_EQ(test::written_frames(r.out), (std::set<int>{1}));
  expect_all_complete(0, 2);
  EXPECT_TRUE(claim_files().empty());
}

}  // namespace
}  // namespace pm
