// Where tests find their data and the pmrender binary: compiled-in paths of the build tree,
// overridable by PM_TEST_DATA_DIR / PM_PMRENDER_BINARY in the environment so a bundled test
// binary also runs on another machine.
#pragma once

#include <cstdlib>
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

}  // namespace pm::test
