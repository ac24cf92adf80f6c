// The CUDA backend: the same device checks as the OpenCL backend. Skipped (and reported as
// skipped by CTest) on machines without a CUDA device.
#include "render/portable_sort.h"
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

TEST_F(CudaBackend, SortsOddDigitCountKeys) {
  test::check_sort_pairs(*device_, 5000, 15, 7);
  test::check_sort_pairs(*device_, 5000, 32, 8);
}

// The portable sort (OpenCL's) from the same kernels on a GPU's warps: its digit lanes read one
// key together and write apart.
TEST_F(CudaBackend, PortableSortSortsPairsStably) {
  PortableSortScratch scratch;
  auto portable = [&](DeviceBuffer& keys_in, DeviceBuffer& values_in, DeviceBuffer& keys_out,
                      DeviceBuffer& values_out, uint32_t count, int key_bits) {
    portable_sort_pairs(*device_, scratch, keys_in, values_in, keys_out, values_out, count, key_bits);
  };
  for (uint32_t count : {1u, 2u, 255u, 257u, 2049u, 100000u, 1048579u})
    test::check_sort_pairs(*device_, count, 30, count, portable);
  test::check_sort_pairs(*device_, 5000, 15, 7, portable);
  test::check_sort_pairs(*device_, 5000, 32, 8, portable);
}

}  // namespace
}  // namespace pm
