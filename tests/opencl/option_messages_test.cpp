// Command-line parse errors as the user meets them: one line starting "pmrender: " that names
// the option or command, exit code 2; numbers are plain decimal, in range and finite.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "support/pmrender_process.h"

namespace pm {
namespace {

using test::ProcessResult;

class OptionMessages : public test::PmrenderProcessTest {
 protected:
  // Exit code 2 and exactly one line on stderr, starting "pmrender: " and containing `expect`.
  void expect_refused(const std::string& args, const std::string& expect) {
    SCOPED_TRACE(args);
    const ProcessResult r = pmrender(args + " -o " + (dir_ / "never_####.exr").string());
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_EQ(r.err.rfind("pmrender: ", 0), 0u) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(expect), std::string::npos) << r.err;
    EXPECT_LT(r.err.size(), 200u) << r.err;
  }
};

TEST_F(OptionMessages, UnsignedOptionsRefuseSignsHexOctalJunkAndOutOfRange) {
  expect_refused("render --photons -1", "--photons: expected a whole number >= 0, got '-1'");
  expect_refused("render --photons +5", "--photons: expected a whole number");
  expect_refused("render --photons 0x100", "--photons: expected a whole number >= 0, got '0x100'");
  expect_refused("render --photons 12abc", "got '12abc'");
  expect_refused("render --photons 1e6", "got '1e6'");
  expect_refused("render --photons 99999999999999999999999", "--photons");
  expect_refused("render --passes 0", "--passes: expected at least 1 pass, got 0");
  expect_refused("render --passes 4294967296", "--passes: expected a whole number from 0 to 4294967295");
  expect_refused("render --seed -3", "--seed: expected a whole number from 0 to 4294967295");
  expect_refused("render --bounces 17", "--bounces: expected 0 to 16, got 17");
  expect_refused("render --k 0", "--k: expected 1 to 256, got 0");
  expect_refused("render --final-gather 70000", "--final-gather: expected 0 to 65536 rays, got 70000");
  expect_refused("render --final-gather 4 --estimator knn", "--final-gather: reads the footprints of --estimator pd");
  expect_refused("render --final-gather 4 --bounces 0", "--final-gather: needs --bounces 1 or more");
  expect_refused("render --method radiosity --final-gather 70000", "--final-gather: expected 0 to 65536 rays, got 70000");
  expect_refused("render --method radiosity --final-gather 4 --bounces 0", "--final-gather: needs --bounces 1 or more");
  expect_refused("render --mirror-depth ' 3'", "--mirror-depth");
  expect_refused("render --device -1", "--device: expected a whole number");
  expect_refused("render --frame -2", "--frame: expected a whole number from 0 to 999999999");
  expect_refused("render --leaf 0x10", "--leaf: expected auto or a positive integer, got '0x10'");
  expect_refused("render --photons-max 0x10", "--photons-max: expected auto or a whole number of photons, got '0x10'");
  expect_refused("render --photons-max 1000", "--photons-max: expected at least --photons (262144), got 1000");
  expect_refused("render --final-gather 4 --photons-max 524288 --photon-sequence halton",
                 "--photons-max: needs --photon-sequence random");
  expect_refused("render --resolution +64x64", "--resolution");
  expect_refused("render --resolution 0x40x40", "--resolution");
}

TEST_F(OptionMessages, FloatOptionsRefuseNonFiniteAndJunk) {
  expect_refused("render --smoothing inf", "--smoothing: expected auto or a positive number, got 'inf'");
  expect_refused("render --smoothing nan", "--smoothing");
  expect_refused("render --smoothing 0", "--smoothing: expected auto or a positive number, got '0'");
  expect_refused("render --overlap -5", "--overlap: expected auto or a positive number, got '-5'");
  expect_refused("render --alpha 1", "--alpha: expected auto or a number between 0 and 1 (exclusive), got '1'");
  expect_refused("render --alpha 0", "--alpha: expected auto or a number between 0 and 1 (exclusive), got '0'");
  expect_refused("render --tile-gather 0", "--tile-gather: expected auto, off or a positive number, got '0'");
  expect_refused("render --tile-gather near", "--tile-gather: expected auto, off or a positive number, got 'near'");
  expect_refused("render --rmax 1e39", "--rmax: expected a finite number");
  expect_refused("render --rmax -1", "--rmax: must be a positive length in metres");
  expect_refused("render --rmax 0x1p3", "--rmax");
  expect_refused("render --radius 2m", "--radius");
  expect_refused("compare a.exr b.exr --threshold nan", "--threshold: expected a finite number >= 0");
  expect_refused("compare a.exr b.exr --ppd -inf", "--ppd: expected a positive finite number");
}

TEST_F(OptionMessages, OctalLookingNumbersAreDecimal) {
  // "010" must be ten photons, not eight (CLI11 alone reads a leading 0 as octal); the EXR header
  // records the settings, which show the photon count actually used.
  const ProcessResult r = pmrender("render --backend opencl --resolution 8x8 --photons 010 --passes 010 -o " +
                                   (dir_ / "f.exr").string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string header = test::read_text(dir_ / "f.exr");
  EXPECT_NE(header.find("photons=10 "), std::string::npos);
  EXPECT_NE(header.find("photons_total"), std::string::npos);
  EXPECT_NE(header.find(std::string("pmrender/passes") + '\0' + "string"), std::string::npos);
}

TEST_F(OptionMessages, UnknownCommandListsTheCommands) {
  expect_refused("bogus", "pmrender: unknown command 'bogus' (commands: render, devices, compare, bench, frames, farm,");
  expect_refused("--bogus", "pmrender: unknown option '--bogus' (commands: render, devices, compare, bench,");
  const ProcessResult none = pmrender("");
  EXPECT_EQ(none.exit_code, 2);
  EXPECT_EQ(none.err, "pmrender: no command given (commands: render, devices, compare, bench, frames, farm, "
                      "export-scene, tradeoff)\n");
}

TEST_F(OptionMessages, OtherParseErrorsAreOneLine) {
  expect_refused("render --no-such-option", "pmrender: ");
  expect_refused("render a.json b.json", "pmrender: ");
  expect_refused("render --estimator nope", "--estimator");
  expect_refused("compare only-one.exr", "pmrender: ");
}

TEST_F(OptionMessages, HelpAndVersionStillExitZero) {
  EXPECT_EQ(pmrender("--help").exit_code, 0);
  EXPECT_EQ(pmrender("--version").exit_code, 0);
  EXPECT_EQ(pmrender("render --help").exit_code, 0);
}

}  // namespace
}  // namespace pm
