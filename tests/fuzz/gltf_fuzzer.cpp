// libFuzzer target for the glTF loader (scene_io/gltf_scene.h, gltf_files.h): the input is a
// glTF document, then optionally a NUL byte and the content of "buffer.bin" beside it, written
// to a private temporary folder. Input starting with the GLB magic "glTF" is written as
// scene.glb, anything else as scene.gltf. The contract checked: every problem is a
// pm::InputError (anything else escapes and crashes the fuzzer), and a scene that loads is
// consistent (indices, materials, finite values, camera).
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <string>

#include "fuzz_support.h"
#include "render/errors.h"
#include "scene_io/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  // A GLB holds binary chunks (with NUL bytes) itself: no separate buffer file then.
  const uint8_t* end = data + size;
  const uint8_t* document_end = glb ? end : std::find(data, end, uint8_t(0));
  const uint8_t* bin = document_end == end ? end : document_end + 1;
  pm::fuzz::write("buffer.bin", bin, size_t(end - bin));
  const std::string scene = pm::fuzz::write(glb ? "scene.glb" : "scene.gltf", data, size_t(document_end - data));
  try {
    pm::SceneLoadReport report;
    pm::fuzz::check_scene(pm::load_scene_file(scene, &report));
  } catch (const pm::InputError&) {
  }
  return 0;
}
