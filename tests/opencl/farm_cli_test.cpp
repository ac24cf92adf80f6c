// `pmrender frames check` and `pmrender farm slurm` as a user meets them, on the OpenCL backend:
// every kind of bad frame named, exit codes for gating, farm options checked by the real render
// parser before anything is written, and the generated script run task by task with bash (what a
// Slurm node does, without Slurm: tests/farm/slurm_localhost_test.sh runs it under a real one),
// writing the same pixels as one process. sbatch itself is replaced by a recording stand-in here.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include "render/exr_io.h"
#include "support/paths.h"
#include "support/pmrender_process.h"
#include "support/same_image.h"

namespace pm {
namespace {

namespace fs = std::filesystem;
using test::ProcessResult;
using test::read_text;

const char kSmall[] = " --backend opencl --resolution 24x18 --photons 3000 --float";

std::string scene_path() { return test::test_data_dir() + "/animation/moving_room.json"; }

std::string frame_name(const std::string& prefix, int frame) {
  char name[64];
  std::snprintf(name, sizeof(name), "%s_%04d.exr", prefix.c_str(), frame);
  return name;
}

class FarmCli : public test::PmrenderProcessTest {
 protected:
  // Every file under the test folder except pmrender's captured output.
  std::set<std::string> files() {
    std::set<std::string> names;
    for (const auto& e : fs::recursive_directory_iterator(dir_)) {
      const std::string name = fs::relative(e.path(), dir_).string();
      if (name != "stdout.txt" && name != "stderr.txt") names.insert(name);
    }
    return names;
  }
  void expect_usage_error(const std::string& args, const std::string& expected) {
    const ProcessResult r = pmrender(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_NE(r.err.find(expected), std::string::npos) << args << "\n" << r.err;
    EXPECT_TRUE(files().empty()) << args;
  }
  // Runs one array task of a generated script as Slurm would: bash, the task's environment.
  int run_task(const fs::path& script, int task, const fs::path& log) {
    const std::string cmd = "cd / && SLURM_ARRAY_JOB_ID=77 SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash '" +
                            script.string() + "' </dev/null >'" + log.string() + "' 2>&1";
    const int status = std::system(cmd.c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  }
};

TEST_F(FarmCli, FramesCheckNamesEveryBadFrameWithItsReason) {
  const std::string pattern = (dir_ / "out" / "f_####.exr").string();
  ASSERT_EQ(pmrender("render " + scene_path() + kSmall + " --frames 0-4 -o " + pattern).exit_code, 0);
  ProcessResult r = pmrender("frames check -o " + pattern + " --frames 0-4 --resolution 24x18");
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_EQ(r.out, "5 frames: 5 complete\n");
  EXPECT_EQ(pmrender("frames check -q -o " + pattern + " --frames 0-4").out, "");

  fs::remove(dir_ / "out" / "f_0002.exr");
  const fs::path cut = dir_ / "out" / "f_0003.exr";
  fs::resize_file(cut, fs::file_size(cut) - 10);  // the last scanline chunk is cut short
  std::ofstream(dir_ / "out" / "f_0004.exr") << "not an image";
  r = pmrender("frames check -o " + pattern + " --frames 0-5");
  EXPECT_EQ(r.exit_code, 1);
  for (const std::string& line : {"frame 2: " + (dir_ / "out" / "f_0002.exr").string() + ": missing",
                                 "frame 3: " + cut.string() + ": truncated",
                                 "frame 4: " + (dir_ / "out" / "f_0004.exr").string() + ": unreadable (not an OpenEXR file)",
                                 std::string("frame 5: "),
                                 std::string("6 frames: 2 complete, 2 missing, 1 truncated, 1 unreadable\n")})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;

  r = pmrender("frames check -o " + pattern + " --frames 0-1 --resolution 32x18");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.out.find("frame 0: " + (dir_ / "out" / "f_0000.exr").string() + ": wrong size (24x18, expected 32x18)"),
            std::string::npos)
      << r.out;
}

TEST_F(FarmCli, FramesCheckUsageErrorsExitWith2) {
  for (const char* args : {"frames check -o f_#.exr --frames 3-1", "frames check -o f.exr --frames 0-1",
                                 "frames check --frames 0", "frames check -o f_#.exr", "frames check -o f_#.exr --frames 0 --resolution 0x4",
                                 "frames"}) {
    const ProcessResult r = pmrender(args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.err;
    EXPECT_FALSE(r.err.empty()) << args;
  }
}

TEST_F(FarmCli, BadOptionsExitWith2BeforeAnythingIsWritten) {
  const std::string base = "farm slurm " + scene_path() + " --chunk 2 --frames 0-5 -o " + (dir_ / "f_####.exr").string() +
                           " --script " + (dir_ / "job.sh").string();
  expect_usage_error(base + " --no-such-option", "render options: The following argument was not expected: --no-such-option");
  expect_usage_error(base + " --estimator sideways", "render options: --estimator");
  expect_usage_error(base + " --resolution 12by4", "--resolution");
  expect_usage_error(base + " --frame 3", "--frame: give the frames with --frames");
  expect_usage_error(base + " --resume", "--resume: farm tasks always resume");
  expect_usage_error(base + " --wait-for-claimed-frames", "--wait-for-claimed-frames: farm tasks always wait");
  expect_usage_error(base + " --stale-claim-after 30", "--stale-claim-after: expected 0 (never) or at least 60");
  expect_usage_error("farm slurm " + scene_path() + " --chunk 2 --frames 20-30 -o " + (dir_ / "f_####.exr").string(),
                     "--frames: '20-30': outside the scene's frames 0-23");
  expect_usage_error(base + " --time-limit 2h", "--time-limit: '2h' is not a Slurm time");
  expect_usage_error(base + " --sbatch mem=1G", "--sbatch: 'mem=1G' is not an sbatch option");
  expect_usage_error(base + " --partition 'a b'", "--partition: 'a b' must be one word");
  expect_usage_error(base + " --chunk 0", "--chunk");
  expect_usage_error("farm slurm " + scene_path() + " --frames 0-5 -o " + (dir_ / "f_#.exr").string(), "--chunk is required");
  expect_usage_error("farm slurm " + scene_path() + " --chunk 2 --frames 0-1 -o " + (dir_ / "single.exr").string(),
                     "has no # for the frame number, but 2 frames are selected");
  expect_usage_error("farm slurm " + (dir_ / "nope.json").string() + " --chunk 2 -o " + (dir_ / "f_#.exr").string(),
                     "nope.json: cannot open");
}

TEST_F(FarmCli, ScriptTasksWriteTheSamePixelsAsOneRun) {
  // Relative scene and output in a folder with a space: the script holds them absolute, quoted.
  const fs::path work = dir_ / "shot one";
  fs::create_directories(work);
  fs::copy(scene_path(), work / "room.json");
  fs::copy(test::test_data_dir() + "/animation/room.obj", work / "room.obj");
  ProcessResult r = test::run_pmrender(std::string("farm slurm room.json --chunk 2 --frames 3-7") + kSmall +
                                           " -o 'frames out/f_####.exr' --script job.sh",
                                       dir_, work);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.out, "wrote job.sh (3 array tasks)\n");
  const std::string script = read_text(work / "job.sh");
  EXPECT_NE(script.find("pmrender=" + fs::absolute(test::pmrender_binary()).string() + "\n"), std::string::npos) << script;
  EXPECT_NE(script.find("pattern='" + (work / "frames out" / "f_####.exr").string() + "'\n"), std::string::npos) << script;
  EXPECT_NE(script.find("render '" + (work / "room.json").string() + "' --backend opencl"), std::string::npos) << script;
  EXPECT_NE(script.find("chunks=(\n  3-4\n  5-6\n  7\n)\n"), std::string::npos) << script;
  EXPECT_NE(script.find("#SBATCH --output=\"" + (work / "frames out" / "logs").string() + "/%x_%A_%a.log\""),
            std::string::npos);
  EXPECT_TRUE(fs::is_directory(work / "frames out" / "logs"));  // sbatch would not create it
  EXPECT_EQ(script.find("--gres"), std::string::npos);

  for (int task = 0; task < 3; ++task) {
    const fs::path log = dir_ / ("task" + std::to_string(task) + ".log");
    ASSERT_EQ(run_task(work / "job.sh", task, log), 0) << read_text(log);
    const std::string text = read_text(log);
    EXPECT_NE(text.find("task 77_" + std::to_string(task) + ", attempt 1"), std::string::npos) << text;
    EXPECT_NE(text.find(" wrote " + (work / "frames out").string()), std::string::npos) << text;  // timestamped
    EXPECT_NE(text.find(task < 2 ? "2 frames: 2 complete" : "1 frame: 1 complete"), std::string::npos) << text;
    EXPECT_NE(text.find("ended with status 0"), std::string::npos) << text;
  }
  // A task run again (a requeue) finds its frames complete and renders nothing.
  const fs::path again = dir_ / "again.log";
  ASSERT_EQ(run_task(work / "job.sh", 1, again), 0);
  EXPECT_NE(read_text(again).find("rendered 0 of 2 frames"), std::string::npos) << read_text(again);
  EXPECT_NE(read_text(again).find("2 already complete"), std::string::npos) << read_text(again);

  const std::string pattern = "'" + (work / "frames out" / "f_####.exr").string() + "'";
  EXPECT_EQ(pmrender("frames check --frames 3-7 --resolution 24x18 -o " + pattern).exit_code, 0);
  ASSERT_EQ(pmrender("render " + scene_path() + kSmall + " --frames 3-7 -o " + (dir_ / "one" / "f_####.exr").string())
                .exit_code,
            0);
  for (int f = 3; f <= 7; ++f)
    test::expect_same_image(read_exr((work / "frames out" / frame_name("f", f)).string()),
                            read_exr((dir_ / "one" / frame_name("f", f)).string()), "frame " + std::to_string(f));
}

TEST_F(FarmCli, TaskFailsWhenOneOfItsFramesIsNotRight) {
  const std::string pattern = (dir_ / "out" / "f_####.exr").string();
  // A complete file of another size: --resume keeps it, the check at the end does not.
  ASSERT_EQ(pmrender("render " + scene_path() + " --backend opencl --resolution 16x12 --photons 1000 --frames 1 -o " +
                     pattern).exit_code, 0);
  ASSERT_EQ(pmrender("farm slurm " + scene_path() + kSmall + " --chunk 2 --frames 0-1 -o " + pattern + " --script " +
                     (dir_ / "job.sh").string()).exit_code, 0);
  const fs::path log = dir_ / "task.log";
  EXPECT_EQ(run_task(dir_ / "job.sh", 0, log), 1);
  const std::string text = read_text(log);
  EXPECT_NE(text.find("frame 1: " + (dir_ / "out" / "f_0001.exr").string() + ": wrong size (16x12, expected 24x18)"),
            std::string::npos) << text;
  EXPECT_NE(text.find("ended with status 1"), std::string::npos) << text;
}

TEST_F(FarmCli, ClusterOptionsReachTheHeaderAndCudaAsksForAGpu) {
  const ProcessResult r = pmrender("farm slurm " + scene_path() + " --chunk 10 -o " + (dir_ / "f_####.exr").string() +
                                   " --backend cuda --partition gpu --time-limit 1-00:00:00 --account vfx "
                                   "--sbatch=--mem=4G --sbatch=--qos=high --max-running 2 --job-name shot12");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* line : {"#SBATCH --gres=gpu:1\n", "#SBATCH --partition=gpu\n", "#SBATCH --time=1-00:00:00\n",
                           "#SBATCH --account=vfx\n", "#SBATCH --mem=4G\n", "#SBATCH --qos=high\n",
                           "#SBATCH --job-name=shot12\n", "#SBATCH --array=0-2%2\n", "  0-9\n  10-19\n  20-23\n",
                           " --backend cuda --frames \"$frames\""})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;
}

TEST_F(FarmCli, SubmitHandsTheScriptToSbatchAndPrintsTheJobId) {
  // A stand-in sbatch on PATH that keeps what it was given.
  const fs::path bin = dir_ / "bin";
  fs::create_directories(bin);
  std::ofstream(bin / "sbatch") << "#!/bin/sh\necho \"$@\" > '" << (dir_ / "args.txt").string() << "'\ncat > '"
                                << (dir_ / "received.sh").string() << "'\necho '4242;cluster'\n";
  fs::permissions(bin / "sbatch", fs::perms::owner_all);
  const std::string path = std::getenv("PATH");
  setenv("PATH", (bin.string() + ":" + path).c_str(), 1);
  const std::string args = "farm slurm " + scene_path() + kSmall + " --chunk 4 --frames 0-7 -o " +
                           (dir_ / "out" / "f_####.exr").string() + " --submit";
  ProcessResult r = pmrender(args);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(read_text(dir_ / "args.txt"), "--parsable\n");
  const std::string script = read_text(dir_ / "received.sh");
  EXPECT_EQ(r.out, script + "submitted job 4242 (2 array tasks, logs in " + (dir_ / "out" / "logs").string() + ")\n");

  // sbatch refusing the job: its message reaches the user, exit 1.
  std::ofstream(bin / "sbatch") << "#!/bin/sh\ncat >/dev/null\necho 'sbatch: error: invalid partition' >&2\nexit 1\n";
  r = pmrender(args);
  setenv("PATH", path.c_str(), 1);
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("sbatch: error: invalid partition"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("pmrender: sbatch failed (exit 1); nothing was submitted"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pm
