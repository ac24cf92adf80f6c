// The CUDA backend: the same device checks as the OpenCL backend. Skipped (and reported as
// skipped by CTest) on machines without a CUDA device.
#include "support/device_checks.h"

namespace pm {
namespace {

class CudaBackend : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = test::open_first_device("cuda");
    if (!device_) GTEST_SKIP() << "no CUDA device on this machine";
  }
  std::unique_ptr<Device> device_;
};

TEST_F(CudaBackend, StructLayoutsAgreeWithHost) { test::check_layout_agrees(*device_); }

TEST_F(CudaBackend, SortsPairsStablyAcrossTileBoundaries) {
  for (uint32_t count : {1u, 2u, 255u, 256u, 257u, 4097u, 100000u}) test::check_sort_pairs(*device_, count, 30, count);
}

TEST_F(CudaBackend, SortsOddDigitCountKeys) { test::check_sort_pairs(*device_, 5000, 10, 7); }

}  // namespace
}  // namespace pm
