#include "edgevio/vision/keyframe_depth.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include <chrono>
#include <cmath>
#include <limits>

namespace edgevio::vision {

namespace {

/// Halves an inverse-depth map and its variance (0 = invalid): each pixel is
/// the inverse-variance mean of its valid 2x2 children, ρ = Σ ρ_c/σ²_c / Σ 1/σ²_c,
/// σ² = 1 / Σ 1/σ²_c.
void poolHalf(cv::Mat* rho, cv::Mat* var) {
  cv::Mat rho_up(rho->rows / 2, rho->cols / 2, CV_32FC1), var_up(rho->rows / 2, rho->cols / 2, CV_32FC1);
  for (int v = 0; v < rho_up.rows; ++v)
    for (int u = 0; u < rho_up.cols; ++u) {
      float wsum = 0.0f, rsum = 0.0f;
      for (int dv = 0; dv < 2; ++dv)
        for (int du = 0; du < 2; ++du) {
          const float s2 = var->at<float>(2 * v + dv, 2 * u + du);
          if (s2 <= 0.0f) continue;
          wsum += 1.0f / s2;
          rsum += rho->at<float>(2 * v + dv, 2 * u + du) / s2;
        }
      rho_up.at<float>(v, u) = wsum > 0.0f ? rsum / wsum : 0.0f;
      var_up.at<float>(v, u) = wsum > 0.0f ? 1.0f / wsum : 0.0f;
    }
  *rho = rho_up;
  *var = var_up;
}

/// Block matching on a rectified pair; fills inverse depth ρ = d/(f·b) and its
/// variance (0 = invalid: d below `min_disparity`).
void inverseDepth(const cv::Mat& left, const cv::Mat& right, double fb, int num_disparities, int block_size,
                  double min_disparity, const VisionOptions& o, cv::Mat* rho, cv::Mat* var) {
  cv::Ptr<cv::StereoBM> bm = cv::StereoBM::create(num_disparities, block_size);
  cv::Mat_<float> disparity;  // a float output skips the biased 1/16-px rounding of CV_16S
  bm->compute(left, right, disparity);
  const auto var0 = static_cast<float>((o.stereo_disparity_sigma / fb) * (o.stereo_disparity_sigma / fb));
  rho->create(disparity.size(), CV_32FC1);
  var->create(disparity.size(), CV_32FC1);
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u) {
      const float d = disparity(v, u);
      const bool ok = d >= min_disparity && d > 0.0f;
      rho->at<float>(v, u) = ok ? static_cast<float>(d / fb) : 0.0f;
      var->at<float>(v, u) = ok ? var0 : 0.0f;
    }
}

/// Level-0 pixels (CV_8UC1, non-zero) whose valid inverse depths within
/// stereo_discontinuity_radius_px span more than stereo_discontinuity_ratio;
/// empty when the test is off.
cv::Mat depthDiscontinuities(const cv::Mat& rho, const cv::Mat& var, const VisionOptions& o) {
  if (o.stereo_discontinuity_ratio <= 0) return {};
  const int side = 2 * o.stereo_discontinuity_radius_px + 1;
  const cv::Mat kernel = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(side, side));
  cv::Mat rho_max, rho_min, rho_or_inf = rho.clone();
  rho_or_inf.setTo(std::numeric_limits<float>::max(), var <= 0.0f);  // invalid pixels take no part
  cv::dilate(rho, rho_max, kernel);
  cv::erode(rho_or_inf, rho_min, kernel);
  return rho_max > static_cast<float>(o.stereo_discontinuity_ratio) * rho_min;
}

}  // namespace

KeyframeDepth computeKeyframeDepth(const EdgePyramid& left, const cv::Mat& right_full, double baseline_m,
                                   const VisionOptions& o) {
  KeyframeDepth out;
  out.baseline_m = baseline_m;
  const auto t0 = std::chrono::steady_clock::now();
  cv::Mat rho, var;  // inverse depth and its variance per level-0 pixel; a variance of 0 marks an invalid pixel
  const double fb0 = left.levels[0].camera.fx * baseline_m;
  inverseDepth(left.levels[0].image, downsample2(right_full), fb0, o.stereo_num_disparities, o.stereo_block_size,
               o.stereo_min_disparity, o, &rho, &var);
  const cv::Mat discontinuous = depthDiscontinuities(rho, var, o);
  out.bm_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  for (std::size_t l = 0; l < left.levels.size(); ++l) {
    if (l > 0) poolHalf(&rho, &var);
    const EdgeLevel& level = left.levels[l];
    const LevelCamera& c = level.camera;
    std::vector<Eigen::Vector3f> pts;
    std::vector<Eigen::Vector2f> normals;
    const bool subpixel = level.dt.hasLines();
    for (int v = 0; v < level.edges.rows && v < rho.rows; ++v) {
      const std::uint8_t* e = level.edges.ptr<std::uint8_t>(v);
      for (int u = 0; u < level.edges.cols && u < rho.cols; ++u) {
        if (!e[u] || var.at<float>(v, u) <= 0.0f) continue;
        if (l == 0 && !discontinuous.empty() && discontinuous.at<std::uint8_t>(v, u)) continue;
        const float z = 1.0f / rho.at<float>(v, u);
        double x = u, y = v;
        if (subpixel) {  // the same sub-pixel edge the current frame's point-to-line residual measures against
          Vec2 edge, n;
          level.dt.nearestLine(u, v, &edge, &n);
          const double d = (Vec2(u, v) - edge).dot(n);
          x -= d * n.x();
          y -= d * n.y();
          normals.emplace_back(static_cast<float>(n.x()), static_cast<float>(n.y()));
        }
        pts.emplace_back(z * static_cast<float>((x - c.cx) / c.fx), z * static_cast<float>((y - c.cy) / c.fy), z);
      }
    }
    out.points.push_back(std::move(pts));
    out.normals.push_back(std::move(normals));
  }
  return out;
}

}  // namespace edgevio::vision
