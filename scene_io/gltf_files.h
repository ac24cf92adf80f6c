// Owns what a glTF scene reads from disk, under the rules the OBJ loader follows: regular files
// only (a FIFO would block forever, a folder made tinygltf allocate without end), paths relative
// to the glTF file's folder unless absolute, and short one-line messages naming the field.
//  - check_gltf_files: the glTF or GLB file itself, its JSON nesting, and every buffer's uri
//    (data URI or file) and byteLength, checked before tinygltf reads anything;
//  - regular_file_callbacks: the file system tinygltf then reads through (buffers and images);
//  - short_tinygltf_message: tinygltf's own error text made one line, data URIs elided.
#pragma once

#include <tiny_gltf.h>

#include <string>

namespace pm {

// Throws InputError "<path>: <what>" or "<path>: buffers[i].uri: <what>" /
// "<path>: buffers[i].byteLength: <what>". Syntax errors of the JSON are left to tinygltf.
void check_gltf_files(const std::string& path);

// Callbacks for tinygltf::TinyGLTF::SetFsCallbacks reading the glTF file at `gltf_path`: only
// regular files exist for it, absolute URIs mean what they say, nothing is written.
// `gltf_path` must outlive the loader (it is the callbacks' user data).
tinygltf::FsCallbacks regular_file_callbacks(const std::string* gltf_path);

// One line of at most 300 characters: lines joined with "; ", every "data:..." URI replaced by
// "data:... (N characters)".
std::string short_tinygltf_message(const std::string& text);

}  // namespace pm
