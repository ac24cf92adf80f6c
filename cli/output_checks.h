// Checks on the files a command will write, made before any expensive work (loading is done,
// the device is not yet open), so that a path that cannot or must not be written is a one-line
// input error (exit code 2) instead of a failure after the render, or worse, a device file or
// pipe replaced by a regular file.
#pragma once

#include <string>
#include <vector>

namespace pm::cli {

// Throws InputError "<option>: '<path>' ..." when path
//   - does not end in `extension` (compared without case, e.g. ".exr");
//   - names a folder (exists as one, or ends in '/');
//   - exists and is not a regular file (a device such as /dev/null, a FIFO, a socket, or a link to
//     one): the atomic write would replace it with a regular file;
//   - has a file name too long for its folder once the writer's temporary suffix is added;
//   - lies under a path component that is a file, or cannot be reached;
//   - lies in a folder where no file can be created: the nearest existing folder on its way is
//     probed by creating and removing an empty hidden file (this catches read-only file systems and
//     permissions, which access() misses for root).
// Folders are probed once per call, however many paths share them.
void check_output_paths(const std::string& option, const std::vector<std::string>& paths,
                        const std::string& extension);

// Throws InputError "<option>: '<path>' is the <role> '<input>' ..." when path names the same file as
// one of the inputs (same file on disk, or the same path once normalised when it does not exist).
struct NamedInput {
  std::string role;  // "reference", "test"
  std::string path;
};
void check_not_an_input(const std::string& option, const std::string& path, const std::vector<NamedInput>& inputs);

}  // namespace pm::cli
