// AtomicFile (atomic_file.h): temporary beside the target, fsync, rename, folder fsync; the
// temporary is registered with interruption.h so that even a hard exit on a signal removes it.
#include "render/atomic_file.h"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "render/interruption.h"

namespace pm {

namespace {

namespace fs = std::filesystem;

std::runtime_error system_error(const std::string& what) { return std::runtime_error(errno_text(what)); }

// Makes a rename durable. Best effort: some file systems refuse fsync on folders.
void sync_folder(const fs::path& folder) {
  const int fd = ::open(folder.empty() ? "." : folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd < 0) return;
  ::fsync(fd);
  ::close(fd);
}

}  // namespace

AtomicFile::AtomicFile(const std::string& target, const std::string& suffix) : target_(target) {
  const fs::path path(target);
  if (!path.parent_path().empty()) {
    std::error_code error;
    fs::create_directories(path.parent_path(), error);
    if (error) throw std::runtime_error("cannot create folder '" + path.parent_path().string() + "': " + error.message());
  }
  // pid and counter keep concurrent writers, in this process or others, off each other's file;
  // the name is hidden and does not end like a finished file.
  static std::atomic<unsigned> counter{0};
  temporary_ = (path.parent_path() / ("." + path.filename().string() + ".tmp-" + std::to_string(::getpid()) + "-" +
                                      std::to_string(counter++) + suffix))
                   .string();
  fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
  if (fd_ < 0) throw system_error("cannot create '" + temporary_ + "'");
  registry_slot_ = register_temporary(temporary_);
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!committed_) ::unlink(temporary_.c_str());
  unregister_temporary(registry_slot_);
}

void AtomicFile::write(const void* data, size_t size) {
  const char* bytes = static_cast<const char*>(data);
  while (size > 0) {
    throw_if_interrupted();
    const ssize_t written = ::write(fd_, bytes, size);
    if (written < 0) {
      if (errno == EINTR) continue;
      throw system_error("write");
    }
    bytes += written;
    size -= size_t(written);
  }
}

void AtomicFile::seek(size_t position) {
  if (::lseek(fd_, off_t(position), SEEK_SET) < 0) throw system_error("seek");
}

void AtomicFile::commit() {
  throw_if_interrupted();
  // fsync first: without it a crash soon after the rename can leave an empty target on some file
  // systems, which is exactly the partial file the rename is meant to avoid.
  if (::fsync(fd_) != 0) throw system_error("fsync");
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) throw system_error("close");
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) throw system_error("cannot rename '" + temporary_ + "' onto it");
  committed_ = true;
  sync_folder(fs::path(target_).parent_path());
}

std::string errno_text(const std::string& what) { return what + ": " + std::strerror(errno); }

void write_file_atomically(const std::string& path, const std::string& text) {
  AtomicFile file(path);
  file.write(text.data(), text.size());
  file.commit();
}

}  // namespace pm
