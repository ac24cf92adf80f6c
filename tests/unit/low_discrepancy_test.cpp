// The first bounce's scrambled Sobol points (kernels/common/low_discrepancy.h): Sobol's second
// dimension against its known first points, the (0,m,2)-net property of every aligned block with
// and without Owen's scrambling, each scrambled point uniform over the keys, two replicates
// independent of each other, the lobe choice that keeps each lobe's points spread, the
// integration error of an integrand with an edge far under independent points', and the pixels of
// a tile (the pixels of one warp) sending their rays together without sharing their errors once a
// replicate fills the shared cells.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <random>
#include <utility>
#include <vector>

// clang-format off
#include "kernels/common/compat_host.h"
#include "kernels/common/low_discrepancy.h"
#include "kernels/common/pixel_order.h"
// clang-format on

namespace {

// Whether points first .. first + 2^m - 1, scrambled as a pixel's are (its tile's keys t0, t1 for
// the first digits, its own k0, k1 for the rest), put exactly one point in every elementary
// interval of area 2^-m (all m + 1 shapes).
bool is_net(uint first, int m, uint t0, uint t1, uint k0, uint k1, bool scrambled)
{
  const uint n = 1u << m;
  for (int j = 0; j <= m; ++j) {
    std::vector<int> count(n, 0);
    for (uint i = first; i < first + n; ++i) {
      uint x = radical_inverse2_bits(i), y = sobol_dimension1_bits(i);
      if (scrambled) {
        x = owen_scramble_bits_split(x, t0, PM_TILE_SHARED_DIGITS, k0);
        y = owen_scramble_bits_split(y, t1, PM_TILE_SHARED_DIGITS, k1);
      }
      const uint a = j == 0 ? 0u : x >> (32 - j), b = m - j == 0 ? 0u : y >> (32 - (m - j));
      if (++count[(a << (m - j)) | b] > 1) return false;
    }
  }
  return true;
}

// A pixel's keys: its tile's and its own, random.
FirstBounceKeys random_keys(std::mt19937& rng)
{
  FirstBounceKeys keys;
  keys.tile = {uint(rng()), uint(rng()), uint(rng()), uint(rng())};
  keys.own = {uint(rng()), uint(rng()), uint(rng()), uint(rng())};
  return keys;
}

TEST(LowDiscrepancy, SobolsSecondDimensionStartsAsKnown)
{
  const double expected[] = {0.0, 0.5, 0.75, 0.25, 0.625, 0.125, 0.375, 0.875, 0.9375, 0.4375};
  for (uint i = 0; i < 10; ++i) EXPECT_EQ(sobol_dimension1_bits(i) / 4294967296.0, expected[i]) << i;
}

TEST(LowDiscrepancy, EveryAlignedBlockIsANetScrambledOrNot)
{
  std::mt19937 rng(11);
  for (int m = 0; m <= 12; ++m)
    for (uint block : {0u, 1u, 7u, 1000u}) {
      const uint first = block << m;
      EXPECT_TRUE(is_net(first, m, 0, 0, 0, 0, false)) << "m " << m << " block " << block;
      for (int s = 0; s < 4; ++s) EXPECT_TRUE(is_net(first, m, rng(), rng(), rng(), rng(), true)) << "m " << m << " block " << block;
    }
  // A block that does not start at a multiple of its size is no net: the test can tell.
  EXPECT_FALSE(is_net(3, 4, 0, 0, 0, 0, false));
}

TEST(LowDiscrepancy, AScrambledPointIsUniformOverTheKeys)
{
  // Index 5's point, over 64,000 keys, in 8 x 8 cells: a chi-square of 63 degrees of freedom
  // (mean 63, standard deviation 11.2); an unscrambled or digit-shifted point would fill few cells.
  std::mt19937 rng(3);
  const int keys = 64000, cells = 64;
  for (uint index : {0u, 5u, 1234u}) {
    std::vector<int> count(cells, 0);
    for (int k = 0; k < keys; ++k) {
      float u0, u1;
      scrambled_sobol2(index, rng(), rng(), rng(), rng(), &u0, &u1);
      ASSERT_GE(u0, 0.0f);
      ASSERT_LT(u0, 1.0f);
      ASSERT_LT(u1, 1.0f);
      count[int(u0 * 8) * 8 + int(u1 * 8)]++;
    }
    double chi2 = 0, expected = double(keys) / cells;
    for (int c : count) chi2 += (c - expected) * (c - expected) / expected;
    EXPECT_LT(chi2, 63 + 5 * 11.2) << "index " << index;
  }
}

// The disc of radius 0.45 about (0.5, 0.5): an integrand with an edge, as visibility makes them.
double disc(float u0, float u1) { return (u0 - 0.5f) * (u0 - 0.5f) + (u1 - 0.5f) * (u1 - 0.5f) < 0.2025f ? 1.0 : 0.0; }

TEST(LowDiscrepancy, AnEdgesIntegralConvergesFarFasterThanWithIndependentPoints)
{
  // 4096 points of one replicate, 200 scrambles: the RMS error against the disc's area against
  // independent points' sqrt(p (1 - p) / n): 0.0011 against 0.0075 (seven times less; scrambled
  // nets' error falls about as n^-3/4 where the integrand has an edge). A scramble that broke
  // the net would not.
  std::mt19937 rng(8);
  const double area = M_PI * 0.2025;
  const int n = 4096, trials = 200;
  double squares = 0;
  for (int t = 0; t < trials; ++t) {
    FirstBounceKeys keys = random_keys(rng);
    double sum = 0;
    for (int i = 0; i < n; ++i) {
      float u0, u1;
      first_bounce_point(keys, 2 * uint(i / 16), 16, uint(i % 16), &u0, &u1);  // the even passes
      sum += disc(u0, u1);
    }
    squares += (sum / n - area) * (sum / n - area);
  }
  const double rms = std::sqrt(squares / trials), independent = std::sqrt(area * (1 - area) / n);
  EXPECT_LT(rms, independent / 3) << "rms " << rms << " independent " << independent;
}

TEST(LowDiscrepancy, EvenAndOddPassesDrawIndependentReplicates)
{
  // The two replicates' errors on the disc are uncorrelated over scrambles, and each pass's
  // sixteen rays are a net of their replicate.
  std::mt19937 rng(21);
  const double area = M_PI * 0.2025;
  const int trials = 400, passes = 64;
  double even_sq = 0, odd_sq = 0, cross = 0;
  for (int t = 0; t < trials; ++t) {
    FirstBounceKeys keys = random_keys(rng);
    double even = 0, odd = 0;
    for (uint pass = 0; pass < uint(passes); ++pass)
      for (uint ray = 0; ray < 16; ++ray) {
        float u0, u1;
        first_bounce_point(keys, pass, 16, ray, &u0, &u1);
        (pass & 1u ? odd : even) += disc(u0, u1);
      }
    even = even / (passes / 2 * 16) - area;
    odd = odd / (passes / 2 * 16) - area;
    even_sq += even * even;
    odd_sq += odd * odd;
    cross += even * odd;
  }
  const double correlation = cross / std::sqrt(even_sq * odd_sq);
  EXPECT_LT(std::fabs(correlation), 4.0 / std::sqrt(double(trials))) << correlation;
  FirstBounceKeys keys = {{1, 2, 3, 4}, {5, 6, 7, 8}};
  for (uint pass : {0u, 1u, 6u, 9u}) {
    std::vector<int> count(16, 0);
    for (uint ray = 0; ray < 16; ++ray) {
      float u0, u1;
      first_bounce_point(keys, pass, 16, ray, &u0, &u1);
      count[int(u0 * 4) * 4 + int(u1 * 4)]++;
    }
    for (int c : count) EXPECT_EQ(c, 1) << "pass " << pass;
  }
}

TEST(LowDiscrepancy, TheLobeChoiceKeepsEachLobesPointsSpread)
{
  // 1024 points, diffuse with probability 0.25: 256 go to the diffuse lobe, stretched back over
  // [0, 1) in the first number; in 16 x 16 cells of the stretched square each holds one.
  FirstBounceKeys keys = {{9, 8, 7, 6}, {1, 3, 5, 7}};
  std::vector<int> diffuse(256, 0);
  int glossy = 0;
  for (uint i = 0; i < 1024; ++i) {
    float u0, u1;
    first_bounce_point(keys, 2 * (i / 16), 16, i % 16, &u0, &u1);
    if (first_bounce_lobe(0.25f, &u0)) {
      ++glossy;
      continue;
    }
    ASSERT_LT(u0, 1.0f);
    diffuse[int(u0 * 16) * 16 + int(u1 * 16)]++;
  }
  EXPECT_EQ(glossy, 768);
  int empty = 0;
  for (int c : diffuse) empty += c == 0;
  EXPECT_EQ(empty, 0);
}

TEST(LowDiscrepancy, APixelsPointsAreANetWhicheverKeysItsTileShares)
{
  // The first PM_TILE_SHARED_DIGITS digits under one key, the rest under another: every aligned
  // block of a pixel's points is still a net.
  std::mt19937 rng(5);
  for (int m = 0; m <= 10; ++m)
    for (int s = 0; s < 8; ++s) {
      FirstBounceKeys keys = random_keys(rng);
      const uint n = 1u << m, block = uint(rng() % 64);
      for (int j = 0; j <= m; ++j) {
        std::vector<int> count(n, 0);
        for (uint i = block * n; i < (block + 1) * n; ++i) {
          float u0, u1;
          first_bounce_point(keys, 2 * (i / n), n, i % n, &u0, &u1);
          const uint a = uint(std::ldexp(double(u0), j)), b = uint(std::ldexp(double(u1), m - j));
          ASSERT_EQ(++count[(a << (m - j)) | b], 1) << "m " << m << " shape " << j;
        }
      }
    }
}

TEST(LowDiscrepancy, ATilesPixelsSendEachRayIntoOneCellOfTheSquare)
{
  // Ray s of a pass leaves every pixel of a tile within the same 2^-4 x 2^-4 cell (about the same
  // direction about each normal: the warp's rays traverse together); pixels of other tiles do not.
  std::mt19937 rng(17);
  const double cells = double(1u << PM_TILE_SHARED_DIGITS);
  FirstBounceKeys a = random_keys(rng), b = random_keys(rng), other = random_keys(rng);
  b.tile = a.tile;
  int same_cell_elsewhere = 0, rays = 0;
  for (uint pass = 0; pass < 8; ++pass)
    for (uint ray = 0; ray < 16; ++ray, ++rays) {
      float a0, a1, b0, b1, o0, o1;
      first_bounce_point(a, pass, 16, ray, &a0, &a1);
      first_bounce_point(b, pass, 16, ray, &b0, &b1);
      first_bounce_point(other, pass, 16, ray, &o0, &o1);
      EXPECT_EQ(int(a0 * cells), int(b0 * cells)) << pass << " " << ray;
      EXPECT_EQ(int(a1 * cells), int(b1 * cells)) << pass << " " << ray;
      EXPECT_NE(a0, b0);  // within the cell each pixel's own
      same_cell_elsewhere += int(a0 * cells) == int(o0 * cells) && int(a1 * cells) == int(o1 * cells);
    }
  EXPECT_LT(same_cell_elsewhere, rays / 8);  // by chance 1 in 256
}

TEST(LowDiscrepancy, ATilesKeyIsTheKeyOfTheWarpThatShadesIt)
{
  // The pixels that share a tile's key (tile_of_pixel) are the work items one 32-wide warp
  // shades in tile order (pixel_of_work_item): items 32 t .. 32 t + 31 are tile t's pixels.
  for (auto [width, height] : {std::pair<uint, uint>{960, 540}, {13, 7}, {8, 4}, {97, 55}}) {
    const uint items = pixel_work_items(width, height);
    ASSERT_EQ(items % (PM_TILE_W * PM_TILE_H), 0u);
    uint covered = 0;
    for (uint item = 0; item < items; ++item) {
      uint pixel;
      if (!pixel_of_work_item(item, width, height, &pixel)) continue;
      ++covered;
      ASSERT_EQ(tile_of_pixel(pixel, width), item / (PM_TILE_W * PM_TILE_H)) << width << "x" << height << " item " << item;
    }
    EXPECT_EQ(covered, width * height);
  }
}

TEST(LowDiscrepancy, ATilesPixelsShareNoErrorOnceAReplicateFillsTheSharedCells)
{
  // Two pixels of a tile integrate the disc (an edge, as visibility makes). Over 4000 tiles their
  // errors after one pass of 16 rays are correlated (they lie in the same cells: 0.63; the test
  // can tell); after 16 passes of one replicate (256 points, every 2^-4 x 2^-4 cell once) they are
  // not (0.02; four passes: 0.38).
  std::mt19937 rng(29);
  const double area = M_PI * 0.2025;
  const int trials = 4000;
  auto correlation = [&](uint passes) {
    double aa = 0, bb = 0, ab = 0;
    for (int t = 0; t < trials; ++t) {
      FirstBounceKeys a = random_keys(rng), b = random_keys(rng);
      b.tile = a.tile;
      double sa = 0, sb = 0;
      for (uint pass = 0; pass < passes; ++pass)
        for (uint ray = 0; ray < 16; ++ray) {
          float u0, u1;
          first_bounce_point(a, 2 * pass, 16, ray, &u0, &u1);
          sa += disc(u0, u1);
          first_bounce_point(b, 2 * pass, 16, ray, &u0, &u1);
          sb += disc(u0, u1);
        }
      const double ea = sa / (16.0 * passes) - area, eb = sb / (16.0 * passes) - area;
      aa += ea * ea;
      bb += eb * eb;
      ab += ea * eb;
    }
    return ab / std::sqrt(aa * bb);
  };
  const uint filled_passes = (1u << (2 * PM_TILE_SHARED_DIGITS)) / 16;  // 16 at 4 shared digits
  const double one_pass = correlation(1), filled = correlation(filled_passes), bound = 4.0 / std::sqrt(double(trials));
  EXPECT_GT(one_pass, bound) << one_pass;
  EXPECT_LT(std::fabs(filled), bound) << filled;
}

}  // namespace
