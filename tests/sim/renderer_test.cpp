// Rendering: stereo block matching on a rendered, rectified pair must agree
// with the ray-cast depth; obstacles keep their clearance from the path.
#include "edgevio/sim/renderer.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/sensor_model.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::sim {
namespace {

struct World {
  camera::StereoRig rig = io::eurocDefaultRig();
  io::Trajectory samples = scenarioSamples("figure8", 14.0, 1.0, rig.T_b_c[0]);
  std::vector<Vec3> path;
  Scene scene;
  World() {
    for (const auto& s : samples) path.push_back(s.T_w_b.translation());
    SceneOptions o;
    o.texture_log2_size = 9;
    scene = buildScene(path, o, 5);
  }
};

const World& world() {
  static const World w;
  return w;
}

TEST(Renderer, BlockMatchingDisparityAgreesWithRayCastDepth) {
  const World& w = world();
  const camera::StereoRectifier rect(w.rig, camera::RectificationOptions{});
  SensorEffects clean;  // no noise, no vignetting: the test isolates geometry
  clean.gain = 0.7;
  int tested_poses = 0;
  for (std::size_t i : {std::size_t{300}, std::size_t{900}, std::size_t{1500}, std::size_t{2300}}) {
    const geometry::SE3 T_w_b = w.samples[i].T_w_b;
    cv::Mat raw[2], rad;
    for (int c = 0; c < 2; ++c) {
      render(w.scene, RayTable(w.rig.cam[c]), T_w_b * w.rig.T_b_c[c], RenderOptions{}, &rad);
      raw[c] = sensorImage(rad, w.rig.cam[c], clean, 0);
    }
    cv::Mat left, right;
    rect.rectify(raw[0], raw[1], &left, &right);
    // Ground truth: z-depth seen by the rectified left camera.
    cv::Mat depth;
    render(w.scene, RayTable(rect.rectifiedCamera()), T_w_b * rect.T_b_rect(0), RenderOptions{}, &rad, &depth);
    const double fb = rect.rectifiedCamera().fx * rect.baseline();
    cv::Mat expected = fb / depth;

    auto bm = cv::StereoBM::create(96, 15);
    cv::Mat disp16;
    bm->compute(left, right, disp16);
    cv::Mat disp;
    disp16.convertTo(disp, CV_32F, 1.0 / 16.0);
    // Exclude depth discontinuities: block matching is undefined where the
    // expected disparity varies by more than 1 px inside the block.
    cv::Mat dmax, dmin;
    const cv::Mat kernel = cv::Mat::ones(15, 15, CV_8U);
    cv::dilate(expected, dmax, kernel);
    cv::erode(expected, dmin, kernel);
    std::vector<float> errors;
    const int border = 60;  // the rectified image border is black
    for (int v = border; v < disp.rows - border; ++v)
      for (int u = border + 96; u < disp.cols - border; ++u) {
        if (disp.at<float>(v, u) <= 0.0f || dmax.at<float>(v, u) - dmin.at<float>(v, u) > 1.0f) continue;
        errors.push_back(std::abs(disp.at<float>(v, u) - expected.at<float>(v, u)));
      }
    if (errors.size() < 20000) continue;  // a view of mostly blank surfaces: not a fair test
    std::sort(errors.begin(), errors.end());
    const float median = errors[errors.size() / 2], p90 = errors[errors.size() * 9 / 10];
    // Block matching resolves 1/16 px steps; on well-textured, smooth depth its
    // error is a fraction of a pixel. Rendering (bilinear textures, remap)
    // adds interpolation blur, not bias.
    EXPECT_LT(median, 0.2f) << "pose " << i;
    EXPECT_LT(p90, 0.6f) << "pose " << i;
    std::printf("pose %zu: %zu pixels, median |d_bm - f b / Z| = %.3f px, 90%% = %.3f px\n", i, errors.size(), median, p90);
    ++tested_poses;
  }
  EXPECT_GE(tested_poses, 3);
}

TEST(Renderer, OutputDoesNotDependOnThreadCount) {
  const World& w = world();
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
  const World& w = world();
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
