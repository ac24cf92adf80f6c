// `pmrender bench` as a user meets it, run as a separate process on the OpenCL backend: the
// table names every stage, --json writes parseable results with positive times and no temporary
// file left behind, the Table 1/3 extras run, and bad options exit 2 with one line naming them.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>

#include "support/paths.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

using BenchResult = test::ProcessResult;
using test::read_text;

class BenchCli : public test::PmrenderProcessTest {
 protected:


  // Files the bench left in dir_ besides the captured output.
  std::vector<std::string> written() {
    std::vector<std::string> names;
    for (auto& entry : fs::directory_iterator(dir_)) {
      std::string name = entry.path().filename().string();
      if (name != "stdout.txt" && name != "stderr.txt") names.push_back(name);
    }
    return names;
  }

  void expect_input_error(const std::string& args, const std::string& expect) {
    BenchResult r = pmrender("bench --backend opencl --resolution 8x8 --photons 100 " + args);
    EXPECT_EQ(r.exit_code, 2) << args << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << args << "\n" << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << args << "\n" << r.err;
    EXPECT_TRUE(written().empty()) << args;
  }

};

TEST_F(BenchCli, CornellBoxPrintsEveryStageAndWritesJson) {
  const fs::path json = dir_ / "bench.json";
  BenchResult r = pmrender("bench --backend opencl --resolution 32x32 --photons 5000 --warmup 1 --repeat 2 --json " +
                           json.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  // The renderer's stages and the photon-mapping method's, in the order they run.
  const std::vector<std::string> stage_names = {"camera", "photon trace", "map: morton", "map: sort",
                                                "footprints", "map: tree", "gather"};
  for (const std::string& stage : stage_names)
    EXPECT_NE(r.out.find("\n" + stage + " "), std::string::npos) << "no row for " << stage << "\n" << r.out;
  for (const char* line : {"frame (sum of stages)", "frame (host wall)", "frames per second", "photons_per_gather=",
                           "peak device memory", "bytes per photon", "passes per frame: 1"})
    EXPECT_NE(r.out.find(line), std::string::npos) << line << "\n" << r.out;

  ASSERT_TRUE(fs::exists(json));
  EXPECT_EQ(written(), std::vector<std::string>{"bench.json"});  // no temporary file left
  const nlohmann::json j = nlohmann::json::parse(read_text(json));
  EXPECT_EQ(j.at("pmrender_version"), PMRENDER_VERSION);
  EXPECT_FALSE(j.at("date").get<std::string>().empty());
  EXPECT_EQ(j.at("scene").at("name"), "cornell-box");
  EXPECT_EQ(j.at("scene").at("source"), "builtin:cornell-box");
  EXPECT_EQ(j.at("settings").at("width"), 32);
  EXPECT_EQ(j.at("settings").at("height"), 32);
  EXPECT_EQ(j.at("settings").at("photons"), 5000);
  EXPECT_EQ(j.at("settings").at("method"), "photon");
  EXPECT_NE(j.at("settings").at("describe").get<std::string>().find("photons=5000"), std::string::npos);
  EXPECT_EQ(j.at("device").at("backend"), "opencl");
  EXPECT_FALSE(j.at("device").at("name").get<std::string>().empty());
  EXPECT_EQ(j.at("frames").at("warmup"), nlohmann::json::array({0}));
  EXPECT_EQ(j.at("frames").at("measured"), nlohmann::json::array({1, 2}));

  const nlohmann::json& stages = j.at("stages");
  ASSERT_EQ(stages.size(), stage_names.size());
  double share = 0;
  for (size_t s = 0; s < stage_names.size(); ++s) {
    const nlohmann::json& row = stages[s];
    EXPECT_EQ(row.at("stage"), stage_names[s]);
    const double median = row.at("median_ms"), lo = row.at("min_ms"), hi = row.at("max_ms");
    EXPECT_GT(median, 0.0) << row;
    EXPECT_LE(lo, median) << row;
    EXPECT_LE(median, hi) << row;
    share += row.at("share").get<double>();
  }
  EXPECT_NEAR(share, 1.0, 1e-9);
  for (const char* frame : {"sum_of_stages", "host_wall"}) {
    const nlohmann::json& t = j.at("frame_ms").at(frame);
    EXPECT_GT(t.at("min").get<double>(), 0.0) << frame;
    EXPECT_LE(t.at("min").get<double>(), t.at("median").get<double>()) << frame;
    EXPECT_LE(t.at("median").get<double>(), t.at("max").get<double>()) << frame;
  }
  EXPECT_GT(j.at("fps").at("host_wall").get<double>(), 0.0);
  EXPECT_EQ(j.at("work").at("unit"), "photon");
  EXPECT_EQ(j.at("work").at("per_frame"), 5000);
  EXPECT_GT(j.at("method_stats").at("hits").at("median").get<double>(), 0.0);
  EXPECT_GT(j.at("counted").at("stats").at("photons_per_gather").get<double>(), 0.0);
  EXPECT_GT(j.at("counted").at("stats").at("shading_points").get<double>(), 0.0);
  EXPECT_GT(j.at("memory").at("peak_bytes").get<double>(), 0.0);
  EXPECT_GT(j.at("memory").at("bytes_per_unit").get<double>(), 0.0);
  EXPECT_EQ(j.at("per_frame").size(), 2u);
}

TEST_F(BenchCli, ThroughputCountsEveryPassOfTheFrame) {
  // The stage timer sums a frame's passes, so a stage's work per frame is its passes' together.
  const fs::path json = dir_ / "bench.json";
  BenchResult r = pmrender("bench --backend opencl --resolution 32x32 --photons 5000 --passes 3 --warmup 0 --repeat 1 "
                           "--json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = nlohmann::json::parse(read_text(json));
  EXPECT_EQ(j.at("work").at("per_frame"), 15000);
  EXPECT_EQ(j.at("work").at("per_pass"), 5000);
  for (const nlohmann::json& row : j.at("stages")) {
    if (row.at("stage") == "photon trace") EXPECT_EQ(row.at("throughput").at("per_frame"), 15000) << row;
    if (row.at("stage") == "gather")  // the shading points of a pass that found a surface, every pass
      EXPECT_EQ(row.at("throughput").at("per_frame"), 3 * j.at("counted").at("stats").at("shading_points").get<double>())
          << row;
  }
}

TEST_F(BenchCli, LeafSweepAndRadiusHistogram) {
  const fs::path json = dir_ / "sweep.json";
  BenchResult r = pmrender("bench --backend opencl --resolution 16x16 --photons 2000 --warmup 0 --repeat 1 "
                           "--leaf-sweep 1,4 --radius-histogram --json " + json.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("FPS_auto / FPS_best"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("0.95 - 1.00"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("> 1.00"), std::string::npos) << r.out;

  const nlohmann::json j = nlohmann::json::parse(read_text(json));
  const nlohmann::json& points = j.at("leaf_sweep").at("points");
  ASSERT_EQ(points.size(), 3u);  // 1, 4 and auto
  EXPECT_EQ(points[0].at("leaf"), 1);
  EXPECT_EQ(points[1].at("leaf"), 4);
  EXPECT_EQ(points[2].at("leaf"), "auto");
  for (const nlohmann::json& p : points) {
    EXPECT_GT(p.at("fps_stages").get<double>(), 0.0) << p;
    EXPECT_GT(p.at("fps_wall").get<double>(), 0.0) << p;
  }
  const int best = j.at("leaf_sweep").at("best_fixed");
  EXPECT_TRUE(best == 1 || best == 4);

  const nlohmann::json& h = j.at("radius_histogram");
  ASSERT_EQ(h.at("bins").size(), 21u);
  uint64_t binned = 0;
  for (const nlohmann::json& b : h.at("bins")) binned += b.at("count").get<uint64_t>();
  EXPECT_GT(binned, 0u);
  EXPECT_EQ(binned, h.at("valid_hits").get<uint64_t>() - h.at("zero_area").get<uint64_t>());
  // The default --rmax clamps every semiaxis, so no radius exceeds it.
  EXPECT_LE(h.at("max_radius").get<double>(), j.at("settings").at("rmax").get<double>() * 1.0001);
}

TEST_F(BenchCli, BadOptionsExitTwoNamingTheOption) {
  expect_input_error("--frames 5-2", "--frames");
  expect_input_error("--frames 100001", "--frames");
  expect_input_error("--repeat 0", "--repeat");
  expect_input_error("--frames 1-3 --repeat 2", "--repeat");
  expect_input_error("--warmup -1", "--warmup");
  expect_input_error("--json " + (dir_ / "missing" / "b.json").string(), "--json");
  expect_input_error("--leaf-sweep 1,0", "--leaf-sweep");
  expect_input_error("--radius-histogram --estimator knn", "--radius-histogram");
}

}  // namespace
}  // namespace pm
