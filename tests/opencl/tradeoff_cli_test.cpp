// `pmrender tradeoff` end to end on PoCL with a tiny grid: the reference is rendered and written,
// every setting gets a row with positive times and finite errors, the JSON's Pareto flags are the
// front of its own numbers, the SVG is well-formed XML (python3's parser), the picks print, a
// reference read back from file gives the same errors' scale, and bad input exits 2 before any
// rendering with nothing written.
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>

#include "render/tradeoff/pareto.h"
#include "support/pmrender_process.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

class TradeoffCli : public test::PmrenderProcessTest {};

TEST_F(TradeoffCli, TinyGridEndToEnd) {
  const fs::path out = dir_ / "sweep";
  const test::ProcessResult r = pmrender(
      "tradeoff --backend opencl --resolution 16x16 --reference-spp 64 --reference-passes 2 --estimators pd,path "
      "--photons 2048,8192 --passes 1,2 --spp 2 --warmup 0 --repeat 1 --budget-ms 100000 --target-error 10 -o " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  for (const char* file : {"reference.exr", "tradeoff.txt", "tradeoff.json", "tradeoff.svg"})
    EXPECT_TRUE(fs::exists(out / file)) << file;
  EXPECT_NE(r.out.find("best within 100000 ms: "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("fastest with relmae <= 10: "), std::string::npos) << r.out;

  const nlohmann::json j = nlohmann::json::parse(test::read_text(out / "tradeoff.json"));
  ASSERT_EQ(j["settings"].size(), 6u) << "pd: 2 photon counts x 2 pass counts; path: 1 spp x 2 pass counts";
  std::vector<TradeoffPoint> points;
  for (const auto& s : j["settings"]) {
    EXPECT_GT(s["device_ms"]["median"].get<double>(), 0.0) << s["label"];
    for (const char* metric : {"relmae", "relmse", "flip", "indirect_bias"})
      EXPECT_TRUE(std::isfinite(s[metric].get<double>())) << s["label"] << " " << metric;
    EXPECT_GT(s["relmae"].get<double>(), 0.0) << "no setting shares the reference's random numbers";
    points.push_back({s["device_ms"]["median"].get<double>(), s["relmae"].get<double>()});
  }
  const std::vector<bool> front = pareto_front(points);
  for (size_t i = 0; i < front.size(); ++i) EXPECT_EQ(j["settings"][i]["pareto"].get<bool>(), front[i]) << i;
  EXPECT_EQ(j["settings"][4]["label"], "path spp=2 x1");

  const std::string check = "python3 -c \"import sys, xml.etree.ElementTree as E; r = E.parse(sys.argv[1]).getroot(); "
                            "sys.exit(0 if r.tag.endswith('svg') else 1)\" " + (out / "tradeoff.svg").string();
  EXPECT_EQ(std::system(check.c_str()), 0) << "the SVG does not parse as XML";

  // The written reference serves as --reference; its size must match the renders'.
  const test::ProcessResult again = pmrender("tradeoff --backend opencl --resolution 16x16 --reference " +
                                             (out / "reference.exr").string() + " --estimators path --spp 2 "
                                             "--passes 1 --warmup 0 --repeat 1 -q -o " + (dir_ / "again").string());
  EXPECT_EQ(again.exit_code, 0) << again.out << again.err;
  const nlohmann::json k = nlohmann::json::parse(test::read_text(dir_ / "again" / "tradeoff.json"));
  EXPECT_NEAR(k["settings"][0]["relmae"].get<double>(), j["settings"][4]["relmae"].get<double>(), 1e-3)
      << "the same setting against the same reference, read back from its float EXR";
}

// Progressive modes are a grid dimension: shrink only where passes > 1 (one shrink pass is the
// average pass), its own label and series, and its footprints shrink: at 8 passes the shrink
// setting has less bias and more noise than the average setting, so their errors differ.
TEST_F(TradeoffCli, ProgressiveModesAreAGridDimension) {
  const fs::path out = dir_ / "modes";
  const test::ProcessResult r = pmrender(
      "tradeoff --backend opencl --resolution 16x16 --reference-spp 16 --reference-passes 2 --estimators pd "
      "--photons 4096 --passes 1,8 --progressive average,shrink --alpha 0.5 --warmup 0 --repeat 1 -q -o " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::read_text(out / "tradeoff.json"));
  ASSERT_EQ(j["settings"].size(), 3u) << j.dump(1);
  EXPECT_EQ(j["settings"][0]["label"], "pd 4096 s=8 x1");
  EXPECT_EQ(j["settings"][1]["label"], "pd 4096 s=8 x8");
  EXPECT_EQ(j["settings"][2]["label"], "pd 4096 s=8 x8 shrink");
  EXPECT_EQ(j["settings"][2]["progressive"], "shrink");
  EXPECT_EQ(j["settings"][2]["alpha"].get<double>(), 0.5);
  EXPECT_NE(j["settings"][1]["relmae"].get<double>(), j["settings"][2]["relmae"].get<double>());
  EXPECT_NE(test::read_text(out / "tradeoff.svg").find("photon pd shrink"), std::string::npos);
}

TEST_F(TradeoffCli, BadInputExitsTwoBeforeRendering) {
  const struct {
    std::string args, message;
  } cases[] = {
      {"--estimators pd", "--reference or --reference-spp: give exactly one"},
      {"--reference-spp 4 --estimators pd,photon", "--estimators: expected pd, knn, radius or path, got 'photon'"},
      {"--reference-spp 4 --photons 100,x", "--photons: expected a comma-separated list"},
      {"--reference-spp 4 --passes 1.5", "--passes: expected whole numbers"},
      {"--reference-spp 4 --metric rmse", "--metric: expected relmae, relmse or flip"},
      {"--reference no_such.exr", "no_such.exr"},
      {"--reference-spp 4 --smoothing 0", "--smoothing: expected a comma-separated list of positive numbers"},
      {"--reference-spp 4 --progressive average,grow", "--progressive: expected average or shrink, got 'grow'"},
      {"--reference-spp 4 --alpha 1", "--alpha: expected a number between 0 and 1"},
  };
  for (const auto& c : cases) {
    const test::ProcessResult r = pmrender("tradeoff --backend opencl --resolution 8x8 " + c.args + " -o " +
                                           (dir_ / "out").string());
    EXPECT_EQ(r.exit_code, 2) << c.args << "\n" << r.out << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "out")) << c.args;
  }
}

}  // namespace
}  // namespace pm
