// Output path checks made before rendering (output_checks.h): extension, kind of an existing
// target, name length, and whether a file can be created where the target will go.
#include "cli/output_checks.h"

#include <fcntl.h>
#include <limits.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <set>

#include "render/errors.h"

namespace pm::cli {

namespace {

namespace fs = std::filesystem;

// The atomic writers (render/exr_io.cpp, render/preview_png.cpp) write "." + name +
// ".tmp-<pid>-<n>" (+ ".png" for previews) beside the target: at most 28 bytes more than the name.
const size_t kTemporaryNameOverhead = 32;

// The path as quoted in a message: control characters (a newline would break the one-line
// message) shown as '?', and at most 120 characters.
std::string shown(const std::string& path) {
  std::string text = path.size() > 120 ? path.substr(0, 57) + "..." + path.substr(path.size() - 60) : path;
  for (char& c : text)
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
  return text;
}

std::string lower(std::string text) {
  for (char& c : text) c = char(std::tolower(static_cast<unsigned char>(c)));
  return text;
}

const char* file_kind(mode_t mode) {
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISFIFO(mode)) return "a FIFO";
  if (S_ISSOCK(mode)) return "a socket";
  return "not a regular file";
}

class OutputChecker {
 public:
  OutputChecker(std::string option, std::string extension) : option_(std::move(option)), extension_(std::move(extension)) {}

  void check(const std::string& path) {
    path_ = path;
    if (path.empty()) fail("is empty: give a file name ending in " + extension_);
    if (path.back() == '/') fail("is a folder name: add a file name ending in " + extension_);
    if (lower(fs::path(path).extension().string()) != extension_) {
      std::string why = "must end in " + extension_;
      if (extension_ == ".exr") why += ": pmrender writes OpenEXR (for a PNG, add --preview NAME.png)";
      fail(why);
    }
    if (path.size() >= PATH_MAX) fail("is longer than the system allows (" + std::to_string(PATH_MAX) + " bytes)");

    struct stat target;
    if (::stat(path.c_str(), &target) == 0) {
      if (S_ISDIR(target.st_mode)) fail("is a folder: give a file name ending in " + extension_);
      if (!S_ISREG(target.st_mode))
        fail(std::string("is ") + file_kind(target.st_mode) +
             ", not a regular file: pmrender replaces its output files and would replace it");
    } else if (errno != ENOENT && errno != ENOTDIR) {
      fail(std::string("cannot be reached (") + std::strerror(errno) + ")");
    }
    check_folder(fs::path(path));
  }

 private:
  [[noreturn]] void fail(const std::string& why) const { throw InputError(option_ + ": '" + shown(path_) + "' " + why); }

  // The nearest existing folder on the way to the target must be a folder in which files can be
  // created; names must fit it.
  void check_folder(const fs::path& target) {
    fs::path folder = target.parent_path();
    std::vector<std::string> missing;  // folders the writer will create, innermost first
    struct stat st;
    while (true) {
      const fs::path probe_path = folder.empty() ? fs::path(".") : folder;
      if (::stat(probe_path.c_str(), &st) == 0) break;
      if (errno == ENOTDIR) {
        // Some component on the way is a file; name the first one from the root.
        fs::path walked;
        for (const fs::path& part : probe_path) {
          walked /= part;
          if (::stat(walked.c_str(), &st) == 0 && !S_ISDIR(st.st_mode))
            fail("cannot be created: '" + shown(walked.string()) + "' is a file, not a folder");
        }
        fail("cannot be created: a part of its folder is a file, not a folder");
      }
      if (errno != ENOENT) fail("cannot be created: folder '" + shown(probe_path.string()) + "': " + std::strerror(errno));
      if (folder.empty() || folder == folder.parent_path())
        fail("cannot be created: folder '" + shown(probe_path.string()) + "' does not exist");
      missing.push_back(folder.filename().string());
      folder = folder.parent_path();
    }
    const fs::path existing = folder.empty() ? fs::path(".") : folder;
    if (!S_ISDIR(st.st_mode)) fail("cannot be created: '" + shown(existing.string()) + "' is a file, not a folder");

    long name_max = ::pathconf(existing.c_str(), _PC_NAME_MAX);
    if (name_max <= 0) name_max = NAME_MAX;
    for (const std::string& name : missing)
      if (name.size() > size_t(name_max))
        fail("cannot be created: folder name '" + shown(name) + "' is longer than " + std::to_string(name_max) + " bytes");
    const std::string name = target.filename().string();
    if (name.size() + kTemporaryNameOverhead > size_t(name_max))
      fail("has a file name of " + std::to_string(name.size()) + " bytes; at most " +
           std::to_string(size_t(name_max) - kTemporaryNameOverhead) + " fit beside the writer's temporary file");

    if (!probed_.insert(existing.string()).second) return;
    const fs::path probe = existing / (".pmrender-probe-" + std::to_string(::getpid()));
    const int fd = ::open(probe.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0600);
    if (fd < 0)
      fail("cannot be written: no file can be created in '" + shown(existing.string()) + "' (" + std::strerror(errno) + ")");
    ::close(fd);
    ::unlink(probe.c_str());
  }

  std::string option_, extension_, path_;
  std::set<std::string> probed_;
};

}  // namespace

void check_output_paths(const std::string& option, const std::vector<std::string>& paths, const std::string& extension) {
  OutputChecker checker(option, lower(extension));
  for (const std::string& path : paths) checker.check(path);
}

void check_not_an_input(const std::string& option, const std::string& path, const std::vector<NamedInput>& inputs) {
  for (const NamedInput& input : inputs) {
    std::error_code ec;
    const bool same = fs::exists(path, ec) && fs::exists(input.path, ec)
                          ? fs::equivalent(path, input.path, ec)
                          : fs::weakly_canonical(path, ec) == fs::weakly_canonical(input.path, ec);
    if (same)
      throw InputError(option + ": '" + shown(path) + "' is the " + input.role + " image '" + shown(input.path) +
                       "': writing it would overwrite that input");
  }
}

}  // namespace pm::cli
