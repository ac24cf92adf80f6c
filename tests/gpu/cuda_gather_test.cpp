// The gather through the photon-map BVH equals brute force over every hit on the CUDA backend
// (CUB sort, concurrent bottom-up pass on a real GPU). Skipped without a CUDA device.
#include "scene_io/cornell_box.h"
#include "support/device_checks.h"
#include "support/gather_checks.h"

namespace pm {
namespace {

PhotonSettings photons(int estimator, int kernel, int leaf) {
  return test::photon_settings(100000, estimator, kernel, leaf, 32);
}

class CudaGather : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = test::open_first_device("cuda");
    if (!device_) GTEST_SKIP() << "no CUDA device on this machine";
  }
  std::unique_ptr<Device> device_;
};

TEST_F(CudaGather, FootprintsEqualBruteForce) {
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), photons(PM_ESTIMATOR_PD, PM_KERNEL_CONSTANT, 1), 32, 32);
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), photons(PM_ESTIMATOR_PD, PM_KERNEL_EPANECHNIKOV, 0), 32, 32);
}
TEST_F(CudaGather, RadiusAndNearestNeighboursEqualBruteForce) {
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), photons(PM_ESTIMATOR_RADIUS, PM_KERNEL_CONSTANT, 8), 32, 32);
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), photons(PM_ESTIMATOR_KNN, PM_KERNEL_CONSTANT, 4), 32, 32);
}

}  // namespace
}  // namespace pm
