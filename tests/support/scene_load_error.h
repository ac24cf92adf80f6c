// The one-line message a scene file is refused with, for the tests of bad input: loading must
// throw InputError; a file that loads is a test failure.
#pragma once

#include <gtest/gtest.h>

#include <string>

#include "render/errors.h"
#include "scene_io/scene_file.h"

namespace pm::test {

// The InputError message from loading path ("" and a test failure if it loads).
inline std::string scene_load_error(const std::string& path) {
  try {
    load_scene_file(path);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "loading " << path << " did not throw InputError";
  return "";
}

}  // namespace pm::test
