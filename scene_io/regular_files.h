// Owns how scene_io reads the files a scene names (glTF files and buffers, texture images): only
// regular files, so a FIFO, a device or a folder named by a scene cannot block or exhaust the
// loader, and a reason in words when a file cannot be read.
#pragma once

#include <sys/types.h>

#include <string>
#include <vector>

namespace pm {

// Reads a whole regular file into *out; "" on success, else the reason ("No such file or
// directory", "is a folder, not a regular file", ...).
std::string read_regular_file(const std::string& path, std::vector<unsigned char>* out);

// "" when path is a regular file (its size in *size), else the reason ("not found", ...).
std::string file_problem(const std::string& path, off_t* size);

}  // namespace pm
