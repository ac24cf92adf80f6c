// 30-bit Morton codes (kernels/common/morton.h): interleaving against a bit-by-bit reference,
// known codes at corners and centre, monotonicity along each axis, degenerate bounds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

// clang-format off
#include "kernels/common/compat_host.h"
#include "kernels/common/vec3.h"
#include "kernels/common/morton.h"
// clang-format on

namespace {

// Bit b of each coordinate goes to bit 3b + 2 (x), 3b + 1 (y), 3b (z).
uint reference_code(uint x, uint y, uint z)
{
  uint code = 0;
  for (uint b = 0; b < 10; ++b)
    code |= (((x >> b) & 1u) << (3 * b + 2)) | (((y >> b) & 1u) << (3 * b + 1)) | (((z >> b) & 1u) << (3 * b));
  return code;
}

const Vec3 kLo = vec3(-2.0f, 0.0f, 10.0f);
const Vec3 kHi = vec3(2.0f, 8.0f, 10.5f);

TEST(Morton, EncodeMatchesBitReference)
{
  std::mt19937 rng(5);
  for (uint x = 0; x < 1024; ++x) ASSERT_EQ(morton_expand_bits(x), reference_code(0, 0, x)) << x;
  for (int i = 0; i < 100000; ++i) {
    uint x = rng() % 1024, y = rng() % 1024, z = rng() % 1024;
    ASSERT_EQ(morton_encode(x, y, z), reference_code(x, y, z));
  }
  EXPECT_EQ(morton_encode(1023, 1023, 1023), 0x3FFFFFFFu);
  EXPECT_EQ(morton_encode(1, 0, 0), 4u);
  EXPECT_EQ(morton_encode(0, 1, 0), 2u);
  EXPECT_EQ(morton_encode(0, 0, 1), 1u);
  EXPECT_EQ(morton_expand_bits(0xFFFFFFFFu), 0x09249249u) << "bits above 10 must be dropped";
}

TEST(Morton, KnownCodesAtCornersAndCentre)
{
  EXPECT_EQ(morton_code(kLo, kLo, kHi), 0u);
  EXPECT_EQ(morton_code(kHi, kLo, kHi), 0x3FFFFFFFu);
  // Centre: cell 512 = bit 9 on every axis -> bits 29, 28, 27.
  EXPECT_EQ(morton_code(vec3(0.0f, 4.0f, 10.25f), kLo, kHi), 0x38000000u);
  // Mixed corner: x high, y low, z high -> every x and z bit set.
  EXPECT_EQ(morton_code(vec3(2.0f, 0.0f, 10.5f), kLo, kHi), 0x2DB6DB6Du);
  // Just below the centre on x: cell 511.
  EXPECT_EQ(morton_code(vec3(-0.001f, 0.0f, 10.0f), kLo, kHi), reference_code(511, 0, 0));
  // Outside the bounds clamps to the border cells.
  EXPECT_EQ(morton_code(vec3(-100.0f, 100.0f, 10.0f), kLo, kHi), reference_code(0, 1023, 0));
}

TEST(Morton, QuantizeMatchesFloorOfScaledPosition)
{
  for (int i = 0; i <= 4096; ++i) {
    float v = -2.0f + 4.0f * (float)i / 4096.0f;  // exact in float
    uint expected = std::min(1023u, (uint)std::floor((v + 2.0f) / 4.0f * 1024.0f));
    ASSERT_EQ(morton_quantize(v, -2.0f, 2.0f), expected) << v;
  }
}

TEST(Morton, MonotonicAlongEachAxis)
{
  std::mt19937 rng(9);
  std::uniform_real_distribution<float> u(0.0f, 1.0f);
  for (int axis = 0; axis < 3; ++axis) {
    for (int trial = 0; trial < 50; ++trial) {
      Vec3 p = vec3(-2.0f + 4.0f * u(rng), 8.0f * u(rng), 10.0f + 0.5f * u(rng));
      uint prev = 0, distinct = 0;
      for (int s = 0; s <= 3000; ++s) {
        float t = (float)s / 3000.0f;
        Vec3 q = p;
        if (axis == 0) q.x = -2.0f + 4.0f * t;
        if (axis == 1) q.y = 8.0f * t;
        if (axis == 2) q.z = 10.0f + 0.5f * t;
        uint code = morton_code(q, kLo, kHi);
        if (s > 0) {
          ASSERT_GE(code, prev) << "axis " << axis << " step " << s;
        }
        distinct += s == 0 || code != prev;
        prev = code;
      }
      EXPECT_EQ(distinct, 1024u) << "every cell along axis " << axis << " is reached";
    }
  }
}

TEST(Morton, DegenerateBoundsGiveFiniteCodes)
{
  const float inf = INFINITY, nan = NAN;
  // All hits at one point: every axis has zero extent.
  EXPECT_EQ(morton_code(vec3(1, 2, 3), vec3(1, 2, 3), vec3(1, 2, 3)), 0u);
  // Flat along y: y contributes nothing, x and z still quantise.
  Vec3 lo = vec3(0, 5, 0), hi = vec3(1, 5, 1);
  EXPECT_EQ(morton_code(vec3(1, 5, 1), lo, hi), reference_code(1023, 0, 1023));
  EXPECT_EQ(morton_code(vec3(0.5f, 7, 0.5f), lo, hi), reference_code(512, 0, 512));
  // Empty box (+inf, -inf) from zero hits, infinite and NaN bounds or positions, tiny extents.
  EXPECT_EQ(morton_code(vec3(1, 2, 3), vec3_splat(inf), vec3_splat(-inf)), 0u);
  EXPECT_EQ(morton_code(vec3(1, 2, 3), vec3_splat(-inf), vec3_splat(inf)), 0u);
  EXPECT_EQ(morton_code(vec3(nan, 0.5f, nan), vec3_splat(0), vec3_splat(1)), reference_code(0, 512, 0));
  EXPECT_EQ(morton_code(vec3(1, 1, 1), vec3_splat(nan), vec3_splat(1)), 0u);
  float tiny = 1e-44f;  // denormal extent: 1024 / extent would overflow
  EXPECT_EQ(morton_code(vec3(tiny, tiny, 0), vec3_splat(0), vec3_splat(tiny)), reference_code(1023, 1023, 0));
  EXPECT_LE(morton_code(vec3(3e38f, -3e38f, 0), vec3_splat(-3e38f), vec3_splat(3e38f)), 0x3FFFFFFFu);
}

}  // namespace
