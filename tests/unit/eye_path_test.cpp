// Tests of the eye path replayed from the shading points (kernels/common/camera_pass.h,
// eye_path_next) on the host, after the camera pass: in a Cornell box whose white surfaces are
// mirrors, every shading point's direction towards the viewer must point at the camera (depth 0)
// or at the previous shading point (behind a mirror), and its weight must be the product of the
// mirror reflectances before it; the frame keeps neither.
#include <gtest/gtest.h>

#include <cmath>

#include "kernels/common/compat_host.h"
#include "kernels/common/camera_pass.h"
#include "scene_io/cornell_box.h"
#include "support/host_render.h"

namespace pm {
namespace {

TEST(EyePath, ReplaysTheDirectionsAndMirrorWeightsOfTheCameraPass) {
  Scene scene = builtin_cornell_box();
  MaterialDesc& white = scene.materials.at(0);  // floor, ceiling, back wall and blocks
  ASSERT_EQ(white.name, "white");
  white.mirror = Float3{0.9f, 0.8f, 0.7f};
  const int width = 24, height = 24, mirror_depth = 3;
  test::HostCameraPass pass(scene, width, height, mirror_depth);
  pass.run();
  const Vec3 camera = vec3_from_float4(pass.p.camera.position);
  int points_behind_mirrors = 0;
  for (uint32_t pixel = 0; pixel < uint32_t(pass.pixels); ++pixel) {
    EyePath eye = eye_path_begin(pixel);
    ShadingPoint sp;
    Vec3 previous = camera, weight = vec3_splat(1.0f);
    while (eye_path_next(&pass.kg, &pass.p, &eye, &sp)) {
      const Vec3 towards_previous = vec3_normalize(vec3_sub(previous, sp.position));
      // Within 2.5 degrees: a reflected ray leaves its mirror a little off the surface (ray.h).
      EXPECT_NEAR(vec3_dot(sp.outgoing, towards_previous), 1.0f, 1e-3f) << "pixel " << pixel << " depth " << eye.depth - 1;
      EXPECT_NEAR(vec3_length(sp.outgoing), 1.0f, 1e-5f);
      EXPECT_GE(vec3_dot(sp.outgoing, sp.normal), 0.0f) << "the normal faces the viewer";
      EXPECT_FLOAT_EQ(sp.weight.x, weight.x);
      EXPECT_FLOAT_EQ(sp.weight.y, weight.y);
      EXPECT_FLOAT_EQ(sp.weight.z, weight.z);
      points_behind_mirrors += eye.depth > 1;
      weight = vec3_mul(weight, material_mirror(&sp.material));
      previous = sp.position;
    }
    EXPECT_LE(eye.depth, uint32_t(mirror_depth + 1));
  }
  EXPECT_GT(points_behind_mirrors, int(pass.pixels) / 2) << "most eye paths see a surface in a mirror";
}

}  // namespace
}  // namespace pm
