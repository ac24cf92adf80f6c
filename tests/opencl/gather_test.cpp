// The gather through the photon-map BVH equals brute force over every hit, on the OpenCL backend,
// for each estimator, both kernels, and leaf thresholds from none to strong fusion.
#include "render/renderer.h"
#include "scene_io/cornell_box.h"
#include "support/analytic_scenes.h"
#include "support/device_checks.h"
#include "support/gather_checks.h"
#include "support/render_settings.h"

namespace pm {
namespace {

class OpenclGather : public ::testing::Test {
 protected:
  void SetUp() override {
    device_ = test::open_first_device("opencl");
    ASSERT_NE(device_, nullptr);
  }
  PhotonSettings photons(int estimator, int kernel, int leaf) {
    return test::photon_settings(20000, estimator, kernel, leaf, 16);
  }
  std::unique_ptr<Device> device_;
};

TEST_F(OpenclGather, FootprintsEqualBruteForceWithoutFusion) {
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), photons(PM_ESTIMATOR_PD, PM_KERNEL_CONSTANT, 1), 24, 24);
}
TEST_F(OpenclGather, FootprintsEqualBruteForceWithFusedLeaves) {
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), photons(PM_ESTIMATOR_PD, PM_KERNEL_EPANECHNIKOV, 16), 24, 24);
}
TEST_F(OpenclGather, AutoLeafSizeEqualsBruteForce) {
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), photons(PM_ESTIMATOR_PD, PM_KERNEL_CONSTANT, 0), 24, 24);
}
TEST_F(OpenclGather, VoxelVolumeHeuristicMapEqualsBruteForce) {
  PhotonSettings p = photons(PM_ESTIMATOR_PD, PM_KERNEL_CONSTANT, 8);
  p.builder = kPhotonMapVvh;
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), p, 24, 24);
}
TEST_F(OpenclGather, RadiusEqualsBruteForce) {
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), photons(PM_ESTIMATOR_RADIUS, PM_KERNEL_CONSTANT, 4), 24, 24);
}
TEST_F(OpenclGather, FacetWeightedGatherOnACurvedSurfaceEqualsBruteForce) {
  // Inside a tessellated sphere every photon's neighbours lie on facets tilted from its own, so the
  // tilt gain (gather_reach.h) weighs nearly every pair: the facet-weighted gather kernel against
  // the brute force's own cos(wi, n) / cos(wi, n_hit), for the radius estimator (on by default)
  // and for pd with --facet-weighting on.
  const Scene sphere = test::diffuse_sphere(2.0f, 0.5f, 3, {100, 100, 100});
  test::check_gather_equals_brute_force(*device_, sphere, photons(PM_ESTIMATOR_RADIUS, PM_KERNEL_CONSTANT, 4), 24, 24);
  PhotonSettings pd = photons(PM_ESTIMATOR_PD, PM_KERNEL_EPANECHNIKOV, 4);
  pd.facet_weighting = 1;
  test::check_gather_equals_brute_force(*device_, sphere, pd, 24, 24);
}
// knn's region is measured again on the host (support/gather_checks.h), without its coverage
// probes: a probe ray that grazes a triangle's edge may hit on the device and miss on the host
// (NVIDIA's OpenCL contracts multiply-adds), and one probe moves a pixel by a few percent. The
// probes are the footprints' (footprint_coverage.h), checked there and by ctest accuracy.
PhotonSettings without_coverage(PhotonSettings p) {
  p.footprint_coverage = false;
  return p;
}
TEST_F(OpenclGather, NearestNeighboursEqualBruteForce) {
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(),
                                        without_coverage(photons(PM_ESTIMATOR_KNN, PM_KERNEL_EPANECHNIKOV, 4)), 24, 24);
}
TEST_F(OpenclGather, NearestNeighboursInAThickRegionEqualBruteForce) {
  // A normal half-axis over the radius above 1: the region's metric is then shorter than the
  // Euclidean distance along the normal, and the traversal must prune with scaled box distances.
  PhotonSettings p = without_coverage(photons(PM_ESTIMATOR_KNN, PM_KERNEL_CONSTANT, 4));
  p.footprint_thickness = 3.0f;
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(), p, 24, 24);
}
TEST_F(OpenclGather, NearestNeighboursWithTheConstantKernelEqualBruteForce) {
  test::check_gather_equals_brute_force(*device_, builtin_cornell_box(),
                                        without_coverage(photons(PM_ESTIMATOR_KNN, PM_KERNEL_CONSTANT, 4)), 24, 24);
}

// The gather's pixel tiles may walk the photon map with their points' box (kernels/common/
// gather_tiles.h; on by default where lanes run in lockstep, forced here on the CPU): each point
// keeps the photons its own walk finds, in its order, so the image is the same bits. Tiles walk
// together for none, some and all of the points (the statistic counts them), for pd with both
// kernels, with facet weighting, and for the fixed radius, in a box with a mirror.
TEST_F(OpenclGather, TilesWalkingTheMapTogetherRenderTheSameBits) {
  const Scene box = builtin_cornell_box();
  PhotonSettings facets = photons(PM_ESTIMATOR_PD, PM_KERNEL_EPANECHNIKOV, 4);
  facets.facet_weighting = 1;
  for (const PhotonSettings& base : {photons(PM_ESTIMATOR_PD, PM_KERNEL_CONSTANT, 0), facets,
                                     photons(PM_ESTIMATOR_RADIUS, PM_KERNEL_CONSTANT, 4)}) {
    std::vector<float> alone, alone_combined;
    double shares[3] = {0, 0, 0};
    const float reaches[3] = {0.0f, 3.0f, 1e6f};
    for (int i = 0; i < 3; ++i) {
      PhotonSettings p = base;
      p.tile_gather = reaches[i];
      RenderSettings settings = test::photon_render_settings(p);
      settings.width = 40;
      settings.height = 28;
      settings.mirror_depth = 1;
      Renderer renderer(*device_, box, settings);
      renderer.set_collect_stats(true);
      const auto frame = renderer.render_frame(2);
      const std::vector<float>& image = frame.find("indirect")->rgb;
      shares[i] = renderer.method()->stats().get("tile_walked_share", -1);
      if (i == 0) {
        alone = image;
        alone_combined = frame.find("")->rgb;
        continue;
      }
      EXPECT_EQ(image, alone) << "tile reach " << reaches[i] << ", estimator " << base.estimator;
      EXPECT_EQ(frame.find("")->rgb, alone_combined) << "tile reach " << reaches[i];
    }
    EXPECT_EQ(shares[0], -1) << "no tile walks without a reach";
    EXPECT_GT(shares[1], 0.05) << "a short reach lets some tiles walk together: " << shares[1] << " of " << shares[2];
    EXPECT_LT(shares[1], shares[2]) << "and not all of them";
    EXPECT_GT(shares[2], 0.7) << "every tile with a first point that is not a mirror's";
  }
}

// The photon map is rebuilt in parallel every frame: the same frame must come out bit-identical,
// whatever order the work items ran in (atomics decide only who finishes a node, not its value).
TEST_F(OpenclGather, SameFrameRendersBitIdentically) {
  RenderSettings settings = test::photon_render_settings(photons(PM_ESTIMATOR_PD, PM_KERNEL_CONSTANT, 0));
  settings.width = 32;
  settings.height = 32;
  Scene scene = builtin_cornell_box();
  Renderer first(*device_, scene, settings);
  std::vector<float> a = first.render_frame(3).find("")->rgb;
  Renderer second(*device_, scene, settings);
  std::vector<float> b = second.render_frame(3).find("")->rgb;
  EXPECT_EQ(a, b);
  std::vector<float> other_frame = second.render_frame(4).find("")->rgb;
  EXPECT_NE(a, other_frame) << "the frame number must reseed the photons";
}

}  // namespace
}  // namespace pm
