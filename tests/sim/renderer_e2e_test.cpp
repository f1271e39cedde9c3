// Rendering: stereo block matching on a rendered, rectified pair must agree
// with the ray-cast depth.
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

TEST(Renderer, BlockMatchingDisparityAgreesWithRayCastDepth) {
  const test::FigureEightWorld& w = test::FigureEightWorld::get();
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

}  // namespace
}  // namespace edgevio::sim
