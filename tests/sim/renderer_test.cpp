// Rendering: the output does not depend on the thread count, obstacles keep
// their clearance from the path, textures tile. (Block matching against the
// ray-cast depth: renderer_e2e_test.cpp.)
#include "edgevio/sim/renderer.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>

#include "common/sim_fixture.h"
#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/sensor_model.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::sim {
namespace {

TEST(Renderer, OutputDoesNotDependOnThreadCount) {
  const test::FigureEightWorld& w = test::FigureEightWorld::get();
  const RayTable rays(w.rig.cam[0]);
  cv::Mat a, b;
  RenderOptions one, three;
  one.threads = 1;
  three.threads = 3;
  render(w.scene, rays, w.samples[700].T_w_b * w.rig.T_b_c[0], one, &a);
  render(w.scene, rays, w.samples[700].T_w_b * w.rig.T_b_c[0], three, &b);
  EXPECT_EQ(cv::norm(a, b, cv::NORM_INF), 0.0);
}

TEST(Scene, ObstaclesKeepTheirClearanceAndTheRoomContainsThePath) {
  const test::FigureEightWorld& w = test::FigureEightWorld::get();
  EXPECT_GE(w.scene.obstacles.size(), 5u);
  for (const SceneBox& b : w.scene.obstacles)
    for (const Vec3& p : w.path) ASSERT_GE(distanceToBox(b, p), 1.0);
  for (const Vec3& p : w.path) {
    EXPECT_TRUE((p.cast<float>().array() > w.scene.room.lo.array()).all());
    EXPECT_TRUE((p.cast<float>().array() < w.scene.room.hi.array()).all());
  }
}

TEST(Texture, TilesSeamlesslyAndHasMipLevels) {
  for (int k = 0; k < kTextureKinds; ++k) {
    const Texture t(static_cast<TextureKind>(k), 8, 4.0, 11);
    // Tiling is seamless when the step across the wrap (last column → first)
    // is no larger than the largest column-to-column step inside the texture.
    const auto columnStep = [&](int x0, int x1) {
      double sum = 0;
      for (int y = 0; y < t.size(); ++y) sum += std::abs(t.texel(x1, y) - t.texel(x0, y));
      return sum;
    };
    double inside = 0;
    for (int x = 1; x < t.size(); ++x) inside = std::max(inside, columnStep(x - 1, x));
    EXPECT_LE(columnStep(t.size() - 1, 0), inside + 1e-6) << "texture kind " << k;
    // A huge footprint samples the 1x1 level: the mean albedo.
    double mean = 0;
    for (int y = 0; y < t.size(); ++y)
      for (int x = 0; x < t.size(); ++x) mean += t.texel(x, y);
    mean /= t.size() * t.size();
    EXPECT_NEAR(t.sample(0.3f, 0.7f, 1000.0f), mean, 2.0 / 255.0) << "texture kind " << k;
  }
}

}  // namespace
}  // namespace edgevio::sim
