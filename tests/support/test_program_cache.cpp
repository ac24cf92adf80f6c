// Linked into every test binary: points the program cache (render/program_cache.h) at a folder
// of this test process under the system's temporary folder before any test runs, so that tests,
// and the pmrender processes they start (which inherit the environment), never write into the
// user's cache; the folder is removed when the process ends. Tests of the cache itself point it
// at folders of their own.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>
#include <string>
#include <system_error>

namespace {

struct TestProgramCache {
  std::filesystem::path folder;
  pid_t owner = 0;

  TestProgramCache() {
    std::error_code ignored;
    folder = std::filesystem::temp_directory_path(ignored) / ("pmrender_test_program_cache_" + std::to_string(getpid()));
    owner = getpid();
    setenv("PMRENDER_CACHE_DIR", folder.c_str(), 1);
    unsetenv("PMRENDER_PROGRAM_CACHE");
  }
  ~TestProgramCache() {
    if (getpid() != owner) return;  // a forked child leaves the folder to its parent
    std::error_code ignored;
    std::filesystem::remove_all(folder, ignored);
  }
};

const TestProgramCache test_program_cache;

}  // namespace
