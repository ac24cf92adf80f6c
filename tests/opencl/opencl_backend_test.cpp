// The OpenCL backend on whatever OpenCL device the machine has (PoCL in CI): the embedded
// program builds, struct layouts agree with the host, launches and the portable sort work.
#include "support/device_checks.h"

namespace pm {
namespace {

class OpenclBackend : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = test::open_first_device("opencl");
    ASSERT_NE(device_, nullptr) << "no OpenCL device: install pocl-opencl-icd";
  }
  std::unique_ptr<Device> device_;
};

TEST_F(OpenclBackend, StructLayoutsAgreeWithHost) { test::check_layout_agrees(*device_); }

// Sizes around the tiles of 256 keys and the scan's chunks of digit counts, up to thousands of
// chunks.
TEST_F(OpenclBackend, SortsPairsStablyAcrossTileBoundaries) {
  for (uint32_t count : {1u, 2u, 255u, 256u, 257u, 2048u, 2049u, 4097u, 100000u, 1048579u})
    test::check_sort_pairs(*device_, count, 30, count);
}

// An odd number of digit passes (15 bits: 3; 32 bits: 7) ends in the output pair as well.
TEST_F(OpenclBackend, SortsOddDigitCountKeys) {
  test::check_sort_pairs(*device_, 5000, 15, 7);
  test::check_sort_pairs(*device_, 5000, 32, 8);
}

TEST_F(OpenclBackend, OutOfRangeDeviceIndexIsAnInputError) {
  EXPECT_THROW(create_device("opencl", 9999), InputError);
}

}  // namespace
}  // namespace pm
