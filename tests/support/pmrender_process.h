// Running the pmrender binary as a user would, from tests: a separate process with no standard
// input, its output captured through files, its exit code returned.
#pragma once

#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <set>
#include <fstream>
#include <sstream>
#include <string>

#include "support/paths.h"

namespace pm::test {

struct ProcessResult {
  int exit_code = -1;
  std::string out, err;
};

inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// stdout and stderr go through dir/stdout.txt and dir/stderr.txt; with a workdir, pmrender runs
// there (relative paths in args resolve against it).
inline ProcessResult run_pmrender(const std::string& args, const std::filesystem::path& dir,
                                  const std::filesystem::path& workdir = {}) {
  const std::filesystem::path out = dir / "stdout.txt", err = dir / "stderr.txt";
  const std::string binary = std::filesystem::absolute(pmrender_binary()).string();
  const std::string cd = workdir.empty() ? "" : "cd '" + workdir.string() + "' && ";
  const std::string cmd = cd + binary + " " + args + " </dev/null >'" + out.string() + "' 2>'" + err.string() + "'";
  const int status = std::system(cmd.c_str());
  ProcessResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

// pmrender started in the background (stdout and stderr as for run_pmrender), for tests that act
// on it while it runs, e.g. send it a signal. The shell execs pmrender, so the pid is pmrender's.
inline pid_t start_pmrender(const std::string& args, const std::filesystem::path& dir) {
  const std::string cmd = "exec " + pmrender_binary() + " " + args + " </dev/null >" + (dir / "stdout.txt").string() +
                          " 2>" + (dir / "stderr.txt").string();
  const pid_t pid = fork();
  if (pid == 0) {
    execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    _exit(127);
  }
  return pid;
}

// Waits for a process of start_pmrender; exit_code is -1 when a signal killed it.
inline ProcessResult wait_pmrender(pid_t pid, const std::filesystem::path& dir) {
  int status = 0;
  ProcessResult r;
  if (waitpid(pid, &status, 0) == pid && WIFEXITED(status)) r.exit_code = WEXITSTATUS(status);
  r.out = read_text(dir / "stdout.txt");
  r.err = read_text(dir / "stderr.txt");
  return r;
}

// Fixture for command-line tests: a fresh folder per test (under this process's temporary folder,
// named after the suite and the test) and pmrender() run with its output captured there.
class PmrenderProcessTest : public ::testing::Test {
 protected:
  void SetUp() override {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ = process_temp_dir() / (std::string(info->test_suite_name()) + "_" + info->name());
    std::filesystem::remove_all(dir_);
    std::filesystem::create_directories(dir_);
  }
  void TearDown() override { std::filesystem::remove_all(dir_); }
  ProcessResult pmrender(const std::string& args) { return run_pmrender(args, dir_); }

  std::filesystem::path dir_;
};

// Frames named by the "wrote ... (frame N, ..." lines of a run's standard output.
inline std::set<int> written_frames(const std::string& stdout_text) {
  std::set<int> frames;
  std::istringstream lines(stdout_text);
  for (std::string line; std::getline(lines, line);) {
    const size_t at = line.find("(frame ");
    if (line.rfind("wrote ", 0) == 0 && at != std::string::npos) frames.insert(std::stoi(line.substr(at + 7)));
  }
  return frames;
}

}  // namespace pm::test
