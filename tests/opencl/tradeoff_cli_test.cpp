// `pmrender tradeoff` end to end on PoCL with a tiny grid: the reference is rendered and written,
// every setting gets a row with positive times and finite errors, the JSON's Pareto flags are the
// front of its own numbers, radiosity is swept beside the photon estimators and the report names
// the fastest method of each error level, the SVG is well-formed XML (python3's parser), the picks print, a
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
// average pass) but for pd, whose one shrink pass differs by its facet weighting; its own label
// and series, and its footprints shrink: at 8 passes the shrink setting has less bias and more
// noise than the average setting, so their errors differ.
TEST_F(TradeoffCli, ProgressiveModesAreAGridDimension) {
  const fs::path out = dir_ / "modes";
  const test::ProcessResult r = pmrender(
      "tradeoff --backend opencl --resolution 16x16 --reference-spp 16 --reference-passes 2 --estimators pd "
      "--photons 4096 --passes 1,8 --progressive average,shrink --alpha 0.5 --warmup 0 --repeat 1 -q -o " +
      out.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::read_text(out / "tradeoff.json"));
  ASSERT_EQ(j["settings"].size(), 4u) << j.dump(1);
  EXPECT_EQ(j["settings"][0]["label"], "pd 4096 s=8 x1");
  EXPECT_EQ(j["settings"][1]["label"], "pd 4096 s=8 x1 shrink");
  EXPECT_EQ(j["settings"][2]["label"], "pd 4096 s=8 x8");
  EXPECT_EQ(j["settings"][3]["label"], "pd 4096 s=8 x8 shrink");
  EXPECT_EQ(j["settings"][3]["progressive"], "shrink");
  EXPECT_EQ(j["settings"][3]["alpha"].get<double>(), 0.5);
  EXPECT_NE(j["settings"][2]["relmae"].get<double>(), j["settings"][3]["relmae"].get<double>());
  EXPECT_NE(test::read_text(out / "tradeoff.svg").find("photon pd shrink"), std::string::npos);
}

// Radiosity is a method of the grid: its element sizes and link directions are grid dimensions,
// one pass each, a series of its own; so is final gathering over the pd map (fg), over its gather
// rays, and over the radiosity solution (radiosity-fg), over edges, directions, rays and passes.
// Per error level the report names the fastest setting of
// all that reaches it: the fastest row of the JSON's own numbers with at most that error.
TEST_F(TradeoffCli, RadiosityIsSweptAndTheFastestMethodOfEachLevelIsNamed) {
  const fs::path out = dir_ / "methods";
  const std::vector<double> levels = {10, 0.5, 0.3, 1e-4};
  const test::ProcessResult r = pmrender(
      "tradeoff --backend opencl --resolution 16x16 --reference-spp 16 --reference-passes 2 "
      "--estimators pd,fg,radiosity,radiosity-fg --photons 4096 --passes 1,2 --final-gather 4 --max-edge 0.2,0.1 "
      "--directions 16,32 "
      "--warmup 0 --repeat 1 "
      "--error-levels 10,0.5,0.3,0.0001 -q -o " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
  const nlohmann::json j = nlohmann::json::parse(test::read_text(out / "tradeoff.json"));
  ASSERT_EQ(j["settings"].size(), 16u) << "pd, fg: 2 pass counts each; radiosity: 2 edges x 2 direction counts, one "
                                          "pass; radiosity-fg: the same x 2 pass counts";
  EXPECT_EQ(j["settings"][2]["label"], "fg 4096 rays=4 x1");
  EXPECT_EQ(j["settings"][2]["final_gather"], 4);
  EXPECT_EQ(j["settings"][3]["label"], "fg 4096 rays=4 x2");
  const nlohmann::json& first = j["settings"][4];
  EXPECT_EQ(first["label"], "radiosity edge=0.2 nC=16");
  EXPECT_EQ(first["estimator"], "radiosity");
  EXPECT_EQ(first["passes"], 1);
  EXPECT_EQ(first["directions"], 16);
  EXPECT_NEAR(first["max_edge"].get<double>(), 0.2, 1e-6);
  EXPECT_FALSE(first.contains("photons"));
  EXPECT_FALSE(first.contains("progressive"));
  EXPECT_EQ(j["settings"][7]["label"], "radiosity edge=0.1 nC=32");
  const nlohmann::json& gathered = j["settings"][9];
  EXPECT_EQ(gathered["label"], "radiosity-fg edge=0.2 nC=16 rays=4 x2");
  EXPECT_EQ(gathered["estimator"], "radiosity-fg");
  EXPECT_EQ(gathered["passes"], 2);
  EXPECT_EQ(gathered["final_gather"], 4);
  EXPECT_EQ(gathered["directions"], 16);
  EXPECT_FALSE(gathered.contains("photons"));
  EXPECT_EQ(j["settings"][15]["label"], "radiosity-fg edge=0.1 nC=32 rays=4 x2");
  for (const auto& s : j["settings"]) EXPECT_TRUE(std::isfinite(s["relmae"].get<double>())) << s["label"];

  ASSERT_EQ(j["fastest"].size(), levels.size());
  for (size_t l = 0; l < levels.size(); ++l) {
    std::string expected;
    double fastest_ms = INFINITY;
    for (const auto& s : j["settings"]) {
      const double ms = s["device_ms"]["median"].get<double>();
      if (s["relmae"].get<double>() <= levels[l] && ms < fastest_ms) fastest_ms = ms, expected = s["label"];
    }
    const nlohmann::json& pick = j["fastest"][l];
    EXPECT_EQ(pick["error"].get<double>(), levels[l]);
    if (expected.empty()) EXPECT_TRUE(pick["setting"].is_null()) << pick.dump();
    else EXPECT_EQ(pick["setting"], expected) << "level " << levels[l];
  }
  EXPECT_FALSE(j["fastest"][0]["setting"].is_null()) << "every setting is within 1000 %";
  EXPECT_TRUE(j["fastest"][3]["setting"].is_null()) << "none within 0.01 % of a 32-path reference";
  EXPECT_NE(test::read_text(out / "tradeoff.txt").find("fastest to each level: 1000% "), std::string::npos);
  EXPECT_NE(test::read_text(out / "tradeoff.svg").find("radiosity"), std::string::npos);
}

TEST_F(TradeoffCli, BadInputExitsTwoBeforeRendering) {
  const struct {
    std::string args, message;
  } cases[] = {
      {"--estimators pd", "--reference or --reference-spp: give exactly one"},
      {"--reference-spp 4 --estimators pd,photon",
       "--estimators: expected pd, knn, radius, fg, path, radiosity or radiosity-fg, got 'photon'"},
      {"--reference-spp 4 --directions 0", "--directions: expected a comma-separated list of positive numbers"},
      {"--reference-spp 4 --max-edge 0.1,-1", "--max-edge: expected a comma-separated list of numbers >= 0"},
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
