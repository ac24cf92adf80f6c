// Temporary file, fsync and rename: the atomic file writer every output uses.
#include "render/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <system_error>

namespace pm {

namespace fs = std::filesystem;

namespace {

// Makes the rename itself durable. Best effort: some file systems refuse fsync on folders.
void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

std::string errno_text(const std::string& what) { return what + ": " + std::strerror(errno); }

AtomicFile::AtomicFile(const fs::path& target) : target_(target) {
  if (!target.parent_path().empty()) {
    std::error_code error;
    fs::create_directories(target.parent_path(), error);
    if (error) throw std::runtime_error("cannot create folder '" + target.parent_path().string() + "': " + error.message());
  }
  // pid and counter keep concurrent writers, in this process or others, off each other's file.
  static std::atomic<unsigned> counter{0};
  path_ = target.parent_path() /
          ("." + target.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++));
  fd_ = ::open(path_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd_ < 0) throw std::runtime_error(errno_text("cannot create '" + path_.string() + "'"));
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(path_.c_str());
}

void AtomicFile::write(const void* data, size_t bytes) {
  const char* p = static_cast<const char*>(data);
  while (bytes > 0) {
    const ssize_t written = ::write(fd_, p, bytes);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(errno_text("cannot write '" + path_.string() + "'"));
    }
    p += written;
    bytes -= size_t(written);
  }
}

void AtomicFile::commit() {
  // fsync first: without it a crash soon after the rename can leave an empty target on some
  // file systems, which is exactly the partial file the rename is meant to avoid.
  if (::fsync(fd_) != 0) throw std::runtime_error(errno_text("cannot fsync '" + path_.string() + "'"));
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw std::runtime_error(errno_text("cannot close '" + path_.string() + "'"));
  if (std::rename(path_.c_str(), target_.c_str()) != 0)
    throw std::runtime_error(errno_text("cannot rename '" + path_.string() + "' onto '" + target_.string() + "'"));
  committed_ = true;
  sync_folder(target_.parent_path());
}

void write_file_atomically(const std::string& path, const std::string& text) {
  AtomicFile file{fs::path(path)};
  file.write(text.data(), text.size());
  file.commit();
}

}  // namespace pm
