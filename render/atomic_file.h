// The one way pmrender writes a file, so that its target is either complete or untouched: the
// data goes to a hidden temporary beside the target (".<name>.tmp-<pid>-<n>"), is flushed to disk
// and renamed onto the target. EXR frames, PNG previews, checkpoints, benchmark JSON and every
// other output go through it.
#pragma once

#include <cstddef>
#include <string>

namespace pm {

class AtomicFile {
 public:
  // Creates missing parent folders and the temporary (suffix is appended to its name, e.g. ".png").
  // Throws std::runtime_error naming what failed.
  explicit AtomicFile(const std::string& target, const std::string& suffix = "");
  // Removes the temporary unless commit() renamed it onto the target.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  const std::string& temporary_path() const { return temporary_; }

  // Writes everything (retrying short writes). A stop request (interruption.h) throws Interrupted
  // before each write, so an interrupted writer leaves no file behind; other failures throw
  // std::runtime_error with the system's reason.
  void write(const void* data, size_t size);
  // Moves the write position (formats such as EXR go back to fill in an offset table).
  void seek(size_t position);

  // fsync, close, rename onto the target, then fsync the folder (best effort) so the rename is
  // durable too. Throws std::runtime_error on failure (the destructor then removes the temporary).
  void commit();

 private:
  std::string target_, temporary_;
  int fd_ = -1;
  int registry_slot_ = -1;
  bool committed_ = false;
};

// text written to path through AtomicFile.
void write_file_atomically(const std::string& path, const std::string& text);

// "what: <strerror(errno)>".
std::string errno_text(const std::string& what);

}  // namespace pm
