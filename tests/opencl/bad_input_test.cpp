// The bad-input corpus (tests/data/bad_input/): malformed scene files and meshes through the
// command line as a user meets them, and malformed --frames specifications through their parser.
// Every case must fail with exit code 2 (InputError for the parser), one line naming the file
// and the line or field, and no output file. The expectations live beside the corpus
// (scenes/EXPECTED.tsv, frame_specs.tsv); every scene file of the corpus must be listed there.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "scene_io/frame_spec.h"
#include "render/errors.h"
#include "support/paths.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

std::string corpus_dir() { return test::test_data_dir() + "/bad_input"; }

std::vector<std::vector<std::string>> read_tsv(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  std::vector<std::vector<std::string>> rows;
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::vector<std::string> cells;
    std::stringstream s(line);
    std::string cell;
    while (std::getline(s, cell, '\t')) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

std::string slurp(const fs::path& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

TEST(BadInput, EveryCorpusSceneIsListed) {
  std::set<std::string> listed;
  for (const auto& row : read_tsv(corpus_dir() + "/scenes/EXPECTED.tsv")) listed.insert(row.at(0));
  size_t files = 0;
  for (const auto& entry : fs::directory_iterator(corpus_dir() + "/scenes")) {
    if (entry.path().extension() != ".json" && entry.path().extension() != ".gltf") continue;
    ++files;
    EXPECT_TRUE(listed.count(entry.path().filename().string())) << entry.path() << " has no expectation";
  }
  EXPECT_EQ(files, listed.size());
  EXPECT_GE(files, 30u);
}

TEST(BadInput, ScenesExitTwoWithOneLineNamingFileAndFieldAndWriteNothing) {
  const fs::path out = test::process_temp_dir() / "pm_bad_input";
  for (const auto& row : read_tsv(corpus_dir() + "/scenes/EXPECTED.tsv")) {
    ASSERT_EQ(row.size(), 2u);
    fs::remove_all(out);
    fs::create_directories(out);
    const std::string cmd = "timeout 60 " + test::pmrender_binary() + " render " + corpus_dir() + "/scenes/" +
                            row[0] + " --backend opencl --resolution 8x8 --photons 64 -o " +
                            (out / "f_####.exr").string() + " </dev/null >" + (out / "stdout").string() + " 2>" +
                            (out / "stderr").string();
    const int status = std::system(cmd.c_str());
    const std::string err = slurp(out / "stderr");
    EXPECT_EQ(WIFEXITED(status) ? WEXITSTATUS(status) : -1, 2) << row[0] << ": " << err;
    EXPECT_NE(err.find(row[1]), std::string::npos) << row[0] << ": expected '" << row[1] << "' in: " << err;
    EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << row[0] << ": " << err;
    bool wrote = false;
    for (const auto& entry : fs::recursive_directory_iterator(out))
      wrote |= entry.path().extension() == ".exr" || entry.path().string().find(".tmp-") != std::string::npos;
    EXPECT_FALSE(wrote) << row[0] << " left an output file";
  }
  fs::remove_all(out);
}

TEST(BadInput, FrameSpecsNameTheOptionAndThePart) {
  const auto rows = read_tsv(corpus_dir() + "/frame_specs.tsv");
  EXPECT_GE(rows.size(), 15u);
  for (const auto& row : rows) {
    ASSERT_EQ(row.size(), 4u);
    const std::string spec = row[0] == "<empty>" ? "" : row[0];
    try {
      parse_frame_spec(spec, std::stoi(row[1]), std::stoi(row[2]));
      ADD_FAILURE() << "'" << spec << "' was accepted";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(row[3]), std::string::npos) << "'" << spec << "': " << e.what();
    }
  }
}

}  // namespace
}  // namespace pm
