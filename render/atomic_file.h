// The one way pmrender writes a file: into a hidden temporary beside the target (same folder, so
// the rename cannot cross file systems), fsync'ed, then renamed onto the target, so a reader or a
// crash never sees a half-written file. EXR frames, benchmark JSON and every other output go
// through it.
#pragma once

#include <filesystem>
#include <string>

namespace pm {

class AtomicFile {
 public:
  // Creates ".<name>.tmp-<pid>-<n>" beside target (its folder is created if missing).
  explicit AtomicFile(const std::filesystem::path& target);
  // Removes the temporary unless commit() renamed it.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  int fd() const { return fd_; }
  const std::filesystem::path& temporary_path() const { return path_; }
  // Writes all of data (retrying short writes); throws std::runtime_error naming the file.
  void write(const void* data, size_t bytes);
  // fsync, close, rename onto the target, fsync the folder: the target now holds the data.
  void commit();

 private:
  std::filesystem::path target_, path_;
  int fd_ = -1;
  bool committed_ = false;
};

// text written to path through AtomicFile.
void write_file_atomically(const std::string& path, const std::string& text);

// "what: <strerror(errno)>".
std::string errno_text(const std::string& what);

}  // namespace pm
