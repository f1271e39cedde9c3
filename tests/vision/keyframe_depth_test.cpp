// Keyframe reference points: where on the image they sit and how deep.
#include "edgevio/vision/keyframe_depth.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "common/render_fixture.h"
#include "edgevio/sim/random.h"
#include "edgevio/vision/edge_pyramid.h"

namespace edgevio::vision {
namespace {

TEST(KeyframeDepth, ReferencePointsSitOnTheSubPixelEdge) {
  // A vertical step between full-resolution columns 81 and 82, i.e. at
  // x = 81.5, lies at x = (81.5 + 0.5) / 2 − 0.5 = 40.5 on level 0 (half
  // resolution): exactly between two pixels, where Canny's pixels are 0.5 px
  // off. The current frame's point-to-line residual measures against the
  // sub-pixel edge, so a reference point must sit on it too, or identical
  // views would align with an offset (with a disparity of 8 level-0 pixels,
  // 0.5 px is 6 % of the depth in lateral position). A faint texture gives
  // block matching something to match in the flat areas.
  constexpr int kW = 160, kH = 120, kDisparityFull = 16;
  sim::Rng rng(3);
  cv::Mat texture(kH, kW + kDisparityFull, CV_32FC1);
  for (int v = 0; v < texture.rows; ++v)
    for (int u = 0; u < texture.cols; ++u) texture.at<float>(v, u) = static_cast<float>(8.0 * rng.uniform());
  cv::GaussianBlur(texture, texture, cv::Size(5, 5), 1.0);
  // Scene columns x_s; the left image sees x_s at x_s, the right at x_s − disparity.
  const auto scene = [&](int x_s, int v) { return (x_s >= 82 ? 180.0f : 60.0f) + texture.at<float>(v, x_s); };
  cv::Mat left_f(kH, kW, CV_32FC1), right_f(kH, kW, CV_32FC1);
  for (int v = 0; v < kH; ++v)
    for (int u = 0; u < kW; ++u) {
      left_f.at<float>(v, u) = scene(u, v);
      right_f.at<float>(v, u) = scene(u + kDisparityFull, v);
    }
  cv::GaussianBlur(left_f, left_f, cv::Size(7, 7), 1.5);
  cv::GaussianBlur(right_f, right_f, cv::Size(7, 7), 1.5);
  cv::Mat left, right;
  left_f.convertTo(left, CV_8UC1);
  right_f.convertTo(right, CV_8UC1);

  camera::CameraModel cam;
  cam.width = kW;
  cam.height = kH;
  cam.fx = cam.fy = 100.0;
  cam.cx = 79.5;
  cam.cy = 59.5;
  VisionOptions o;
  o.levels = 2;
  o.stereo_num_disparities = 16;
  const double baseline = 0.1;
  const EdgePyramid pyr = buildEdgePyramid(left, cam, o);
  ASSERT_TRUE(pyr.levels[0].dt.hasLines());
  const KeyframeDepth depth = computeKeyframeDepth(pyr, right, baseline, o);
  const LevelCamera& c0 = pyr.levels[0].camera;
  const double z_true = c0.fx * baseline / (kDisparityFull / 2.0);

  int on_step = 0;
  double sum_u = 0.0, worst = 0.0;
  for (const Eigen::Vector3f& P : depth.points[0]) {
    const double u = c0.fx * P.x() / P.z() + c0.cx, v = c0.fy * P.y() / P.z() + c0.cy;
    if (std::abs(u - 40.5) > 2.0 || v < 8 || v > kH / 2 - 8) continue;  // the step, away from the borders
    ++on_step;
    sum_u += u;
    worst = std::max(worst, std::abs(u - 40.5));
    EXPECT_NEAR(P.z(), z_true, 0.1 * z_true);
  }
  ASSERT_GE(on_step, 30);
  // The parabola through the gradient magnitude of a blurred step is exact up
  // to the texture's perturbation; Canny's pixels would be 0.5 px off.
  EXPECT_NEAR(sum_u / on_step, 40.5, 0.1);
  EXPECT_LT(worst, 0.25);
}

/// A level-0 reference point's estimated / true depth, and whether it lies
/// on a smooth surface (true depth within 3 % in a 7x7 window; at occlusion
/// boundaries block matching fattens the foreground).
struct DepthRatio {
  double ratio;
  bool smooth;
};

/// The depth ratios of every reference point on frames of the figure8
/// render, one list per option set; each frame is rendered once for all.
std::vector<std::vector<DepthRatio>> depthRatios(const test::RenderFixture& fx, const std::vector<VisionOptions>& options) {
  const camera::CameraModel& cam = fx.rectifier().rectifiedCamera();
  std::vector<std::vector<DepthRatio>> ratios(options.size());
  for (std::size_t k = 300; k < fx.path().size(); k += 300) {
    const geometry::SE3& T_w_b = fx.path()[k].T_w_b;
    const tracking::StereoFrame f = fx.frame(T_w_b);
    const cv::Mat z_true = fx.rectifiedDepth(T_w_b);
    for (std::size_t i = 0; i < options.size(); ++i) {
      const EdgePyramid pyr = buildEdgePyramid(f.left, cam, options[i]);
      const KeyframeDepth depth = computeKeyframeDepth(pyr, f.right.get(), fx.rectifier().baseline(), options[i]);
      for (const Eigen::Vector3f& P : depth.points[0]) {
        const auto u = static_cast<int>(std::lround(cam.fx * P.x() / P.z() + cam.cx));
        const auto v = static_cast<int>(std::lround(cam.fy * P.y() / P.z() + cam.cy));
        if (u < 3 || v < 3 || u >= z_true.cols - 3 || v >= z_true.rows - 3) continue;
        double lo, hi;
        cv::minMaxLoc(z_true(cv::Rect(u - 3, v - 3, 7, 7)), &lo, &hi);
        ratios[i].push_back({P.z() / z_true.at<float>(v, u), hi - lo < 0.03 * lo});
      }
    }
  }
  return ratios;
}

double median(std::vector<double> x) {
  std::nth_element(x.begin(), x.begin() + static_cast<std::ptrdiff_t>(x.size() / 2), x.end());
  return x[x.size() / 2];
}

TEST(KeyframeDepth, DepthOnARenderedSceneIsUnbiased) {
  // A depth bias is a scale bias of every tracking link, which the IMU cannot
  // see at constant velocity. OpenCV's fixed-point disparity rounds up:
  // floor(16·d + 15/16) / 16 is on average 7/256 ≈ 0.027 px too large, i.e.
  // 0.3 % too shallow at this room's level-0 disparities of about 9 px, and
  // the EuRoC renders' motion came out 0.4-0.6 % short. The median must be
  // within 0.15 %, the spread of the per-frame medians here.
  const test::RenderFixture fx;
  const std::vector<DepthRatio> all = depthRatios(fx, {VisionOptions{}})[0];
  std::vector<double> ratios;
  for (const DepthRatio& r : all)
    if (r.smooth) ratios.push_back(r.ratio);
  ASSERT_GE(ratios.size(), 10000u);
  EXPECT_NEAR(median(ratios), 1.0, 0.0015);
}

TEST(KeyframeDepth, NoReferencePointsAtDepthDiscontinuities) {
  // A 13 px block straddling an occlusion boundary matches the foreground
  // (foreground fattening): edges of the background beside it get its depth,
  // and a boundary's own edge pixels either depth. Such points move with the
  // wrong parallax as the camera translates, a bias that grows with the
  // link. Leaving out every pixel whose valid inverse depths within 9 px span
  // more than a factor 1.3 must remove most of the points whose depth is off
  // by more than 10 %, and keep most of those on smooth surfaces.
  const test::RenderFixture fx;
  VisionOptions off;
  off.stereo_discontinuity_ratio = 0.0;
  const std::vector<std::vector<DepthRatio>> ratios = depthRatios(fx, {VisionOptions{}, off});
  // The share of points off by more than 10 %, and the number on smooth surfaces.
  const auto wrongShare = [](const std::vector<DepthRatio>& r) {
    const auto wrong = std::count_if(r.begin(), r.end(), [](const DepthRatio& x) { return std::abs(x.ratio - 1.0) > 0.1; });
    return static_cast<double>(wrong) / static_cast<double>(r.size());
  };
  const auto smooth = [](const std::vector<DepthRatio>& r) {
    return static_cast<std::size_t>(std::count_if(r.begin(), r.end(), [](const DepthRatio& x) { return x.smooth; }));
  };
  const double wrong_on = wrongShare(ratios[0]), wrong_off = wrongShare(ratios[1]);
  const std::size_t n_on = ratios[0].size(), n_off = ratios[1].size();
  const std::size_t smooth_on = smooth(ratios[0]), smooth_off = smooth(ratios[1]);
  std::printf("points off by > 10 %%: %.2f %% of %zu with the discontinuity test, %.2f %% of %zu without; smooth-surface points kept %zu of %zu\n",
              100 * wrong_on, n_on, 100 * wrong_off, n_off, smooth_on, smooth_off);
  EXPECT_LT(wrong_on, 0.5 * wrong_off);
  EXPECT_GT(static_cast<double>(smooth_on), 0.8 * static_cast<double>(smooth_off));
}

}  // namespace
}  // namespace edgevio::vision
