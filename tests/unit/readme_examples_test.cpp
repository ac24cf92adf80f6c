// The README's examples work in a clone of the repository alone: every scene file they name by a
// repository path exists and loads without reading outside the repository (the paper's benchmark
// scenes read meshes from ../shared/scenes, which a clone does not have). Names without a folder
// (scene.json) are placeholders.
#include <gtest/gtest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "render/errors.h"
#include "scene_io/scene_file.h"
#include "support/paths.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

TEST(ReadmeExamples, SceneFilesTheyNameShipWithTheRepository) {
  const fs::path root = fs::weakly_canonical(fs::path(test::test_data_dir()) / ".." / "..");
  const std::string readme = test::read_text(root / "README.md");
  ASSERT_FALSE(readme.empty());
  size_t examples = 0, scenes = 0;
  std::istringstream lines(readme);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("pmrender ", 0) != 0) continue;
    ++examples;
    std::istringstream words(line.substr(0, line.find('#')));
    for (std::string word, previous; words >> word; previous = word) {
      const std::string extension = fs::path(word).extension().string();
      if (word.find('/') == std::string::npos || previous == "-o" || previous == "--diff" ||
          (extension != ".json" && extension != ".gltf" && extension != ".glb"))
        continue;
      ++scenes;
      SCOPED_TRACE(line);
      ASSERT_TRUE(fs::is_regular_file(root / word)) << word;
      if (extension == ".json") {
        const nlohmann::json scene = nlohmann::json::parse(test::read_text(root / word));
        for (const nlohmann::json& mesh : scene.value("meshes", nlohmann::json::array())) {
          const fs::path file = fs::weakly_canonical((root / word).parent_path() / mesh.at("file").get<std::string>());
          EXPECT_EQ(file.string().rfind(root.string() + "/", 0), 0u) << file << " is outside the repository";
        }
      }
      EXPECT_GT(load_scene_file((root / word).string()).triangle_count(), 0u);
    }
  }
  EXPECT_GE(examples, 5u);
  EXPECT_GE(scenes, 1u);
}

}  // namespace
}  // namespace pm
