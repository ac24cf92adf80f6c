// Checkpoint state files (render/checkpoint.h): what write_checkpoint writes reads back exactly,
// and every way a file can be wrong (a header line missing, repeated, malformed or out of range,
// pass counts that the pass loop cannot produce, film sums short, long or not finite) is refused
// with its reason, never thrown.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <limits>
#include <string>

#include "render/checkpoint.h"
#include "support/paths.h"

namespace pm {
namespace {

namespace fs = std::filesystem;

const char kFingerprint[] = "cornell-box (built-in) photon pd";

FrameCheckpoint sample_checkpoint() {
  FrameCheckpoint c;
  c.frame = 7;
  c.width = 3;
  c.height = 2;
  c.seconds = 1.25;
  c.fingerprint = kFingerprint;
  c.sums.passes = 5;
  c.sums.odd_passes = 2;
  for (std::vector<float4>* sum : {&c.sums.indirect, &c.sums.caustic, &c.sums.odd})
    for (int i = 0; i < 6; ++i) sum->push_back(float4{0.5f * float(i), 1.0f, 2.0f, 0.0f});
  return c;
}

class Checkpoint : public ::testing::Test {
 protected:
  void SetUp() override {
    path_ = (test::process_temp_dir() / ("checkpoint_" + std::to_string(counter_++) + ".pmstate")).string();
    write_checkpoint(path_, sample_checkpoint());
    std::ifstream in(path_, std::ios::binary);
    bytes_.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    header_ = bytes_.substr(0, bytes_.find("end\n") + 4);
    sums_ = bytes_.substr(header_.size());
  }
  void TearDown() override { fs::remove(path_); }

  // The reason read_checkpoint gives for the file holding `bytes` (empty when it accepts it).
  std::string refusal(const std::string& bytes) {
    std::ofstream(path_, std::ios::binary | std::ios::trunc) << bytes;
    std::string why;
    const auto c = read_checkpoint(path_, 7, 3, 2, kFingerprint, &why);
    return c ? "" : why;
  }
  // The header with one line replaced (by nothing, when `by` is empty).
  std::string header_with(const std::string& line, const std::string& by) {
    std::string h = header_;
    const size_t at = h.find(line + "\n");
    EXPECT_NE(at, std::string::npos) << line;
    h.replace(at, line.size() + 1, by.empty() ? "" : by + "\n");
    return h;
  }

  static int counter_;
  std::string path_, bytes_, header_, sums_;
};
int Checkpoint::counter_ = 0;

TEST_F(Checkpoint, WhatIsWrittenReadsBackExactly) {
  std::string why;
  const auto c = read_checkpoint(path_, 7, 3, 2, kFingerprint, &why);
  ASSERT_TRUE(c) << why;
  const FrameCheckpoint expected = sample_checkpoint();
  EXPECT_EQ(c->seconds, expected.seconds);
  EXPECT_EQ(c->sums.passes, 5u);
  EXPECT_EQ(c->sums.odd_passes, 2u);
  ASSERT_EQ(c->sums.odd.size(), 6u);
  EXPECT_EQ(std::memcmp(c->sums.indirect.data(), expected.sums.indirect.data(), 6 * sizeof(float4)), 0);
  const auto header = read_checkpoint_header(path_, &why);
  ASSERT_TRUE(header) << why;
  EXPECT_EQ(header->fingerprint, kFingerprint);
  EXPECT_TRUE(header->sums.indirect.empty());
}

TEST_F(Checkpoint, AnotherFrameSizeOrFingerprintIsRefused) {
  std::string why;
  EXPECT_FALSE(read_checkpoint(path_, 8, 3, 2, kFingerprint, &why));
  EXPECT_EQ(why, "it is frame 7's");
  EXPECT_FALSE(read_checkpoint(path_, 7, 2, 3, kFingerprint, &why));
  EXPECT_EQ(why, "it has another resolution");
  EXPECT_FALSE(read_checkpoint(path_, 7, 3, 2, "other", &why));
  EXPECT_EQ(why, "it was rendered with other settings or another scene");
}

TEST_F(Checkpoint, FilmSumsMustFillTheFileExactly) {
  EXPECT_EQ(refusal(header_ + sums_.substr(0, sums_.size() - 1)), "truncated film sums");
  EXPECT_EQ(refusal(header_), "truncated film sums");
  EXPECT_EQ(refusal(header_.substr(0, header_.size() - 1)), "truncated film sums");
  EXPECT_EQ(refusal(header_ + sums_ + "x"), "trailing bytes after the film sums");
  EXPECT_EQ(refusal(header_ + sums_ + sums_), "trailing bytes after the film sums");
}

TEST_F(Checkpoint, NonFiniteFilmSumsAreRefused) {
  std::string sums = sums_;
  const float nan = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&sums[sums.size() - 12], &nan, sizeof(float));  // the odd sum's last pixel, y
  EXPECT_EQ(refusal(header_ + sums), "its film sums are not finite");
}

TEST_F(Checkpoint, EveryHeaderLineIsRequiredOnce) {
  for (const std::string line : {"frame 7", "size 3 2", "passes 5 2", "seconds 1.25"}) {
    const std::string key = line.substr(0, line.find(' '));
    EXPECT_EQ(refusal(header_with(line, "") + sums_), "no " + key + " line in the header");
    EXPECT_EQ(refusal(header_with(line, line + "\n" + line) + sums_), "repeated header line '" + line + "'");
  }
  EXPECT_EQ(refusal(header_with(std::string("fingerprint ") + kFingerprint, "") + sums_), "no fingerprint line in the header");
  EXPECT_EQ(refusal(header_with("frame 7", "colour 7") + sums_), "unknown header line 'colour 7'");
  EXPECT_EQ(refusal("pmrender checkpoint 2\n"), "not a pmrender checkpoint");
  EXPECT_EQ(refusal(header_.substr(0, header_.size() - 4)), "truncated header");
}

TEST_F(Checkpoint, NumbersArePlainDecimalInRange) {
  for (const std::string bad : {"frame 7x", "frame +7", "frame  7", "frame 99999999999"})
    EXPECT_EQ(refusal(header_with("frame 7", bad) + sums_), "bad header line '" + bad + "'");
  for (const std::string bad : {"size 3", "size 3 2 1", "size 0 2", "size -3 2", "size 3  2"})
    EXPECT_EQ(refusal(header_with("size 3 2", bad) + sums_), "bad header line '" + bad + "'");
  // "-1" would wrap to 4294967295 in an unsigned stream read.
  for (const std::string bad : {"passes -1 2", "passes 5", "passes 5 2 0", "passes 4294967296 2"})
    EXPECT_EQ(refusal(header_with("passes 5 2", bad) + sums_), "bad header line '" + bad + "'");
  for (const std::string bad : {"seconds nan", "seconds inf", "seconds -1", "seconds 1e999", "seconds 1,5"})
    EXPECT_EQ(refusal(header_with("seconds 1.25", bad) + sums_), "bad header line '" + bad + "'");
}

TEST_F(Checkpoint, PassCountsMustBeOnesThePassLoopProduces) {
  EXPECT_EQ(refusal(header_with("passes 5 2", "passes 0 0") + sums_), "it holds no pass");
  EXPECT_EQ(refusal(header_with("passes 5 2", "passes 5 3") + sums_), "its pass counts disagree");
  EXPECT_EQ(refusal(header_with("passes 5 2", "passes 5 7") + sums_), "its pass counts disagree");
  EXPECT_EQ(refusal(header_with("passes 5 2", "passes 6 3") + sums_), "");
}

TEST_F(Checkpoint, AMissingFileIsRefused) {
  std::string why;
  EXPECT_FALSE(read_checkpoint(path_ + ".none", 7, 3, 2, kFingerprint, &why));
  EXPECT_EQ(why, "no checkpoint");
  EXPECT_FALSE(read_checkpoint_header(path_ + ".none", &why));
}

}  // namespace
}  // namespace pm
