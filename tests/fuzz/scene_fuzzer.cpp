// libFuzzer target for the scene parser: load_scene_file on a JSON scene, an OBJ mesh and an MTL
// file written to a private temporary folder. Input layout: JSON, then optionally a NUL byte and
// the OBJ text ("mesh.obj"), then optionally a NUL byte and the MTL text ("mesh.mtl").
// The contract checked: every problem is a pm::InputError (anything else escapes and crashes
// the fuzzer), and a scene that loads is consistent (indices, materials, finite values).
#include <algorithm>
#include <cstdint>
#include <string>

#include "fuzz_support.h"
#include "render/errors.h"
#include "scene_io/scene_file.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const uint8_t* end = data + size;
  const uint8_t* json_end = std::find(data, end, uint8_t(0));
  const uint8_t* obj = json_end == end ? end : json_end + 1;
  const uint8_t* obj_end = std::find(obj, end, uint8_t(0));
  const uint8_t* mtl = obj_end == end ? end : obj_end + 1;
  const std::string scene = pm::fuzz::write("scene.json", data, size_t(json_end - data));
  pm::fuzz::write("mesh.obj", obj, size_t(obj_end - obj));
  pm::fuzz::write("mesh.mtl", mtl, size_t(end - mtl));
  try {
    pm::SceneLoadReport report;
    pm::fuzz::check_scene(pm::load_scene_file(scene, &report));
  } catch (const pm::InputError&) {
  }
  return 0;
}
