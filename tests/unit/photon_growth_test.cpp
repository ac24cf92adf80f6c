// Final gathering's photons a pass that grow with the frame (PhotonSettings::photons_in_pass,
// photons_before_pass, photons_max_or_default) and the settings' checks of --photons-max.
#include <gtest/gtest.h>

#include <cstdint>

#include "render/errors.h"
#include "render/photon/photon_settings.h"

namespace pm {
namespace {

PhotonSettings final_gathering(uint64_t photons) {
  PhotonSettings s;
  s.photons = photons;
  s.final_gather = 16;
  return s;
}

TEST(PhotonGrowth, FinalGatheringDoublesAtTheStartAndEachTimeThePassesQuadruple) {
  const PhotonSettings s = final_gathering(262144);
  EXPECT_EQ(s.photons_max_or_default(), 1048576u);
  EXPECT_EQ(s.photons_in_pass(0), 262144u);
  EXPECT_EQ(s.photons_in_pass(kPhotonGrowthStart - 1), 262144u);
  EXPECT_EQ(s.photons_in_pass(kPhotonGrowthStart), 524288u);
  EXPECT_EQ(s.photons_in_pass(4 * kPhotonGrowthStart - 1), 524288u);
  EXPECT_EQ(s.photons_in_pass(4 * kPhotonGrowthStart), 1048576u);
  // At the most from then on, however long the frame.
  EXPECT_EQ(s.photons_in_pass(16 * kPhotonGrowthStart), 1048576u);
  EXPECT_EQ(s.photons_in_pass(4000000000u), 1048576u);
}

TEST(PhotonGrowth, EachPassStartsWhereTheOnesBeforeItEnded) {
  // A pass's photons are numbered after all earlier passes' photons: no two passes share a
  // random stream, and the sum in closed runs agrees with the passes counted one by one.
  for (const uint64_t most : {uint64_t(0), uint64_t(1000), uint64_t(3000), uint64_t(1) << 20}) {
    PhotonSettings s = final_gathering(1000);
    s.photons_max = most;
    uint64_t sum = 0;
    for (uint32_t pass = 0; pass < 40 * kPhotonGrowthStart; ++pass) {
      ASSERT_EQ(s.photons_before_pass(pass), sum) << "pass " << pass << ", most " << most;
      sum += s.photons_in_pass(pass);
    }
  }
}

TEST(PhotonGrowth, AMostThatIsNoPowerOfTwoCapsTheLastDoubling) {
  PhotonSettings s = final_gathering(1000);
  s.photons_max = 3000;
  EXPECT_EQ(s.photons_in_pass(kPhotonGrowthStart), 2000u);
  EXPECT_EQ(s.photons_in_pass(4 * kPhotonGrowthStart), 3000u);
  EXPECT_EQ(s.photons_in_pass(64 * kPhotonGrowthStart), 3000u);
}

TEST(PhotonGrowth, OnlyFinalGatheringWithRandomPhotonsGrowsByDefault) {
  PhotonSettings plain;  // photon mapping read at the shading point
  EXPECT_EQ(plain.photons_max_or_default(), plain.photons);
  EXPECT_EQ(plain.photons_in_pass(10 * kPhotonGrowthStart), plain.photons);
  EXPECT_EQ(plain.photons_before_pass(1000), 1000 * plain.photons);
  PhotonSettings halton = final_gathering(262144);
  halton.sequence = PM_PHOTON_SEQUENCE_HALTON;
  EXPECT_EQ(halton.photons_max_or_default(), 262144u);
  // Never past kPhotonGrowthMost by default, and never below --photons.
  EXPECT_EQ(final_gathering(65536).photons_max_or_default(), 262144u);
  EXPECT_EQ(final_gathering(2097152).photons_max_or_default(), 2097152u);
  EXPECT_EQ(final_gathering(0).photons_in_pass(5000), 0u);
}

TEST(PhotonGrowth, AMostBelowThePhotonsOrWithHaltonPhotonsIsRefusedNamingTheOption) {
  PhotonSettings below = final_gathering(262144);
  below.photons_max = 1000;
  EXPECT_THROW(
      {
        try {
          below.validate();
        } catch (const SettingError& e) {
          EXPECT_NE(std::string(e.what()).find("photons-max"), std::string::npos) << e.what();
          throw;
        }
      },
      SettingError);
  PhotonSettings halton = final_gathering(262144);
  halton.sequence = PM_PHOTON_SEQUENCE_HALTON;
  halton.photons_max = 524288;
  EXPECT_THROW(halton.validate(), SettingError);
  halton.photons_max = 262144;  // the same count every pass: allowed
  EXPECT_NO_THROW(halton.validate());
  PhotonSettings huge = final_gathering(262144);
  huge.photons_max = uint64_t(1) << 30;
  EXPECT_THROW(huge.validate(), SettingError);
}

}  // namespace
}  // namespace pm
