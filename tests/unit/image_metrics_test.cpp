// Image metrics (render/image_metrics.h) and `pmrender compare` as a user meets it: values of
// the plain metrics on constructed images, bad input named precisely, exit codes 0 / 1 / 2, the
// chosen metric printed last, and the error map written with --diff (and nothing on bad input).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>

#include <OpenEXR/ImfChannelList.h>
#include <OpenEXR/ImfFrameBuffer.h>
#include <OpenEXR/ImfHeader.h>
#include <OpenEXR/ImfOutputFile.h>

#include "render/errors.h"
#include "render/exr_io.h"
#include "render/image_metrics.h"
#include "support/paths.h"
#include "support/test_folder.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

std::vector<float> ramp(int w, int h, float scale) {
  std::vector<float> rgb(size_t(w) * h * 3);
  for (size_t i = 0; i < rgb.size(); ++i) rgb[i] = scale * float(1 + i % 17) / 17.0f;
  return rgb;
}

std::string message_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "(no InputError)";
}

TEST(ImageMetrics, IdenticalImagesScoreZero) {
  std::vector<float> a = ramp(20, 10, 3.0f);
  ImageComparison c = compare_images(a, a, 20, 10);
  EXPECT_EQ(c.flip, 0.0);
  EXPECT_EQ(c.rmse, 0.0);
  EXPECT_EQ(c.relmse, 0.0);
  EXPECT_EQ(c.mean, 0.0);
  EXPECT_EQ(c.relmae, 0.0);
  EXPECT_EQ(c.flip_map.size(), 200u);
}

TEST(ImageMetrics, PlainMetricsHaveTheirDefinitions) {
  std::vector<float> ref(3 * 4, 1.0f), test = ref;
  for (float& v : test) v = 1.05f;
  ImageComparison c = compare_images(ref, test, 2, 2);
  EXPECT_NEAR(c.rmse, 0.05, 1e-6);
  EXPECT_NEAR(c.relmse, 0.05 * 0.05 / 1.01, 1e-6);
  EXPECT_NEAR(c.mean, 0.05, 1e-6);
  EXPECT_NEAR(c.mean_map[3], 0.05, 1e-6);
  EXPECT_NEAR(c.value(ImageMetric::rmse), c.rmse, 0);
  // Noise with zero mean: rmse sees it, the relative mean difference does not.
  std::vector<float> noisy = ref;
  for (size_t i = 0; i < noisy.size(); ++i) noisy[i] += (i % 2 ? 0.1f : -0.1f);
  ImageComparison n = compare_images(ref, noisy, 2, 2);
  EXPECT_NEAR(n.rmse, 0.1, 1e-6);
  EXPECT_NEAR(n.mean, 0.0, 1e-6);
  EXPECT_NEAR(n.relmae, 0.1, 1e-6);  // and the relative mean absolute error does
  EXPECT_NEAR(n.value(ImageMetric::relmae), n.relmae, 0);
  EXPECT_GT(n.flip, 0.0);
}

TEST(ImageMetrics, MetricNamesRoundTripAndBadNamesNameTheOption) {
  for (ImageMetric m :
       {ImageMetric::flip, ImageMetric::rmse, ImageMetric::relmse, ImageMetric::mean, ImageMetric::relmae})
    EXPECT_EQ(parse_image_metric(image_metric_name(m)), m);
  EXPECT_EQ(message_of([] { parse_image_metric("psnr"); }).rfind("metric: ", 0), 0u);
}

TEST(ImageMetrics, NonFiniteValuesAreReportedWithTheirPixel) {
  std::vector<float> rgb(3 * 6, 0.5f);
  rgb[3 * 4 + 1] = std::numeric_limits<float>::quiet_NaN();  // pixel 4 of a 3-wide image: (1, 1)
  EXPECT_EQ(message_of([&] { require_finite(rgb, 3, "a.exr", "combined"); }),
            "a.exr: layer combined: pixel (1, 1) channel G is NaN");
  rgb[3 * 4 + 1] = 0.5f;
  rgb[2] = -std::numeric_limits<float>::infinity();
  EXPECT_EQ(message_of([&] { require_finite(rgb, 3, "b.exr", "direct"); }),
            "b.exr: layer direct: pixel (0, 0) channel B is -Inf");
  rgb[2] = 0;
  EXPECT_NO_THROW(require_finite(rgb, 3, "b.exr", "direct"));
}

TEST(ImageMetrics, MissingLayerListsTheFilesLayers) {
  FrameImage image;
  image.width = image.height = 1;
  image.layers = {{"", {0, 0, 0}}, {"direct", {0, 0, 0}}};
  EXPECT_EQ(&require_layer(image, "combined", "x.exr"), &image.layers[0]);
  EXPECT_EQ(&require_layer(image, "direct", "x.exr"), &image.layers[1]);
  EXPECT_EQ(message_of([&] { require_layer(image, "caustic", "x.exr"); }),
            "x.exr: no layer 'caustic' (the file has: combined, direct)");
}

TEST(ImageMetrics, ErrorMapIsGrey) {
  FrameImage map = error_map_image({0.25f, 0.5f}, 2, 1);
  ASSERT_EQ(map.layers.size(), 1u);
  EXPECT_EQ(map.layers[0].rgb, (std::vector<float>{0.25f, 0.25f, 0.25f, 0.5f, 0.5f, 0.5f}));
}

// --- pmrender compare ----------------------------------------------------------------------------

struct Result {
  int exit_code = -1;
  std::string out, err;
};

class CompareCli : public test::FolderTest {
 protected:
  CompareCli() : FolderTest("pm_compare_") {}

  std::string write(const std::string& name, int w, int h, const std::vector<float>& rgb, bool with_direct = false) {
    FrameImage image;
    image.width = w;
    image.height = h;
    image.layers.push_back({"", rgb});
    if (with_direct) image.layers.push_back({"direct", rgb});
    const std::string path = (dir_ / name).string();
    write_exr(path, image, true);
    return path;
  }

  // write_exr refuses non-finite values, so files holding them are written with OpenEXR itself.
  std::string write_raw(const std::string& name, int w, int h, const std::vector<float>& rgb) {
    const std::string path = (dir_ / name).string();
    Imf::Header header(w, h);
    for (const char* c : {"R", "G", "B"}) header.channels().insert(c, Imf::Channel(Imf::FLOAT));
    Imf::FrameBuffer fb;
    for (int k = 0; k < 3; ++k)
      fb.insert(std::string(1, "RGB"[k]), Imf::Slice(Imf::FLOAT, (char*)(rgb.data() + k), 3 * sizeof(float),
                                                      3 * sizeof(float) * size_t(w)));
    Imf::OutputFile file(path.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(h);
    return path;
  }

  Result compare(const std::string& args) {
    const std::string cmd = test::pmrender_binary() + " compare " + args + " </dev/null >" + (dir_ / "out").string() +
                            " 2>" + (dir_ / "err").string();
    int status = std::system(cmd.c_str());
    Result r;
    r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    std::ifstream o(dir_ / "out"), e(dir_ / "err");
    std::stringstream so, se;
    so << o.rdbuf();
    se << e.rdbuf();
    r.out = so.str();
    r.err = se.str();
    return r;
  }

  void expect_input_error(const std::string& args, const std::string& expect) {
    Result r = compare(args + " --diff " + (dir_ / "diff.exr").string());
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "diff.exr"));
  }
};

TEST_F(CompareCli, PassesUnderThresholdFailsOverAndPrintsTheChosenMetricLast) {
  std::vector<float> ref = ramp(16, 16, 2.0f), test = ref;
  for (float& v : test) v *= 1.3f;
  const std::string a = write("a.exr", 16, 16, ref), b = write("b.exr", 16, 16, test);

  Result same = compare(a + " " + a);
  EXPECT_EQ(same.exit_code, 0) << same.err;
  EXPECT_NE(same.out.find("flip 0 <= threshold 0.05: pass"), std::string::npos) << same.out;

  Result over = compare(a + " " + b + " --metric mean --threshold 0.1");
  EXPECT_EQ(over.exit_code, 1) << over.err;
  // Every metric is printed; the chosen one comes last before the verdict.
  const size_t flip_at = over.out.find("\nflip "), mean_at = over.out.find("\nmean ");
  ASSERT_NE(flip_at, std::string::npos) << over.out;
  ASSERT_NE(mean_at, std::string::npos) << over.out;
  EXPECT_LT(flip_at, mean_at);
  EXPECT_NE(over.out.find("mean 0.3 > threshold 0.1: FAIL"), std::string::npos) << over.out;

  Result under = compare(a + " " + b + " --metric mean --threshold 0.31");
  EXPECT_EQ(under.exit_code, 0) << under.out;
}

TEST_F(CompareCli, RelMaeAndTheSignedBiasesOfTheLight) {
  // Reference: combined 2, direct 1 (indirect 1). Test: combined 1.8, direct 1 (indirect 0.8).
  std::vector<float> ref(3 * 16, 2.0f), test(3 * 16, 1.8f), direct(3 * 16, 1.0f);
  FrameImage r, t;
  r.width = t.width = 4;
  r.height = t.height = 4;
  r.layers = {{"", ref}, {"direct", direct}};
  t.layers = {{"", test}, {"direct", direct}};
  const std::string a = (dir_ / "a.exr").string(), b = (dir_ / "b.exr").string();
  write_exr(a, r, true);
  write_exr(b, t, true);
  Result res = compare(a + " " + b + " --metric relmae --threshold 0.2");
  EXPECT_EQ(res.exit_code, 0) << res.err;
  EXPECT_NE(res.out.find("relmae 0.1 <= threshold 0.2: pass"), std::string::npos) << res.out;
  EXPECT_NE(res.out.find("bias    -10.0000% image mean, -20.0000% indirect light"), std::string::npos) << res.out;
  EXPECT_EQ(compare(a + " " + b + " --metric relmae --threshold 0.05").exit_code, 1);
}

TEST_F(CompareCli, DiffWritesThePerPixelErrorOfTheChosenMetric) {
  std::vector<float> ref = ramp(8, 4, 1.0f), test = ref;
  test[0] += 0.6f;
  const std::string a = write("a.exr", 8, 4, ref), b = write("b.exr", 8, 4, test);
  const std::string diff = (dir_ / "maps" / "d.exr").string();
  Result r = compare(a + " " + b + " --metric rmse --threshold 1 --diff " + diff);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  FrameImage map = read_exr(diff);
  ASSERT_EQ(map.width, 8);
  const std::vector<float>& grey = map.find("")->rgb;
  EXPECT_NEAR(grey[0], 0.6f / std::sqrt(3.0f), 1e-5f);  // root of the channel-mean square
  EXPECT_EQ(grey[1], grey[0]);
  EXPECT_EQ(grey[3], 0.0f);
}

TEST_F(CompareCli, ComparesTheNamedLayer) {
  std::vector<float> ref = ramp(8, 8, 1.0f);
  const std::string a = write("a.exr", 8, 8, ref, true), b = write("b.exr", 8, 8, ref, true);
  Result r = compare(a + " " + b + " --layer direct");
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("layer direct"), std::string::npos) << r.out;
  expect_input_error(a + " " + b + " --layer caustic", "a.exr: no layer 'caustic' (the file has: combined, direct)");
}

TEST_F(CompareCli, BadInputExitsTwoNamingTheFile) {
  std::vector<float> ref = ramp(8, 8, 1.0f), bad = ref;
  const std::string a = write("a.exr", 8, 8, ref);
  const std::string small = write("small.exr", 4, 8, ramp(4, 8, 1.0f));
  bad[3 * (2 * 8 + 5) + 0] = std::numeric_limits<float>::infinity();
  const std::string inf = write_raw("inf.exr", 8, 8, bad);
  std::ofstream(dir_ / "junk.exr") << "not an exr";

  expect_input_error(a + " " + (dir_ / "missing.exr").string(), "missing.exr");
  expect_input_error(a + " " + (dir_ / "junk.exr").string(), "junk.exr");
  expect_input_error(a + " " + small, "small.exr: image is 4x8 but the reference");
  expect_input_error(a + " " + inf, "inf.exr: layer combined: pixel (5, 2) channel R is +Inf");
  expect_input_error(inf + " " + a, "inf.exr: layer combined: pixel (5, 2)");
  expect_input_error(a + " " + a + " --threshold -1", "--threshold");
  expect_input_error(a + " " + a + " --ppd 0", "--ppd");
  Result usage = compare(a + " " + a + " --metric psnr");
  EXPECT_EQ(usage.exit_code, 2);
}

}  // namespace
}  // namespace pm
