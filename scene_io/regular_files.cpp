// Regular-file reads for scene_io (regular_files.h).
#include "scene_io/regular_files.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace pm {

// Reads a whole regular file; "" on success, else the reason. O_NONBLOCK so that a FIFO that
// slipped in between a check and the open cannot block; fstat decides on the open file itself.
std::string read_regular_file(const std::string& path, std::vector<unsigned char>* out) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (fd < 0) return std::strerror(errno);
  struct stat st;
  std::string problem;
  if (::fstat(fd, &st) != 0) problem = std::strerror(errno);
  else if (S_ISDIR(st.st_mode)) problem = "is a folder, not a regular file";
  else if (!S_ISREG(st.st_mode)) problem = "is not a regular file (a device, FIFO or socket)";
  if (problem.empty()) {
    out->resize(size_t(st.st_size));
    size_t done = 0;
    while (done < out->size()) {
      const ssize_t n = ::read(fd, out->data() + done, out->size() - done);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        problem = n < 0 ? std::strerror(errno) : "the file shrank while it was read";
        break;
      }
      done += size_t(n);
    }
  }
  ::close(fd);
  return problem;
}

std::string file_problem(const std::string& path, off_t* size) {
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) return errno == ENOENT ? "not found" : std::strerror(errno);
  if (S_ISDIR(st.st_mode)) return "is a folder, not a regular file";
  if (!S_ISREG(st.st_mode)) return "is not a regular file (a device, FIFO or socket)";
  *size = st.st_size;
  return "";
}

}  // namespace pm
