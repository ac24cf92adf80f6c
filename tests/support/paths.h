// Where tests find their data and the pmrender binary: compiled-in paths of the build tree,
// overridable by PM_TEST_DATA_DIR / PM_PMRENDER_BINARY in the environment so a bundled test
// binary also runs on another machine.
#pragma once

#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>

namespace pm::test {

inline std::string test_data_dir() {
  const char* env = std::getenv("PM_TEST_DATA_DIR");
  return env ? env : PM_TEST_DATA_DIR;
}

inline std::string pmrender_binary() {
  const char* env = std::getenv("PM_PMRENDER_BINARY");
  return env ? env : PM_PMRENDER_BINARY;
}

// A temporary folder of this test process, so concurrent test runs never share files.
inline std::filesystem::path process_temp_dir() {
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("pmrender_test_" + std::to_string(getpid()));
  std::filesystem::create_directories(dir);
  return dir;
}

}  // namespace pm::test
