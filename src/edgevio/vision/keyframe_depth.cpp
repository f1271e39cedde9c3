#include "edgevio/vision/keyframe_depth.h"

#include <opencv2/calib3d.hpp>

#include <chrono>

namespace edgevio::vision {

KeyframeDepth computeKeyframeDepth(const EdgePyramid& left, const cv::Mat& right_level0, double baseline_m,
                                   const VisionOptions& o) {
  KeyframeDepth out;
  const auto t0 = std::chrono::steady_clock::now();
  cv::Ptr<cv::StereoBM> bm = cv::StereoBM::create(o.stereo_num_disparities, o.stereo_block_size);
  cv::Mat_<float> disparity;  // a float output skips the biased 1/16-px rounding of CV_16S
  bm->compute(left.levels[0].image, right_level0, disparity);
  out.bm_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();

  // Level 0 inverse depth and variance; a variance of 0 marks an invalid pixel.
  const LevelCamera& c0 = left.levels[0].camera;
  const double fb = c0.fx * baseline_m;
  const auto var0 = static_cast<float>((o.stereo_disparity_sigma / fb) * (o.stereo_disparity_sigma / fb));
  cv::Mat rho(disparity.size(), CV_32FC1), var(disparity.size(), CV_32FC1);
  for (int v = 0; v < disparity.rows; ++v)
    for (int u = 0; u < disparity.cols; ++u) {
      const float d = disparity(v, u);
      const bool ok = d >= o.stereo_min_disparity && d > 0.0f;
      rho.at<float>(v, u) = ok ? static_cast<float>(d / fb) : 0.0f;
      var.at<float>(v, u) = ok ? var0 : 0.0f;  // 0 = invalid
    }

  for (std::size_t l = 0; l < left.levels.size(); ++l) {
    if (l > 0) {  // pool children: ρ = Σ ρ_c / σ²_c / Σ 1/σ²_c, σ² = 1 / Σ 1/σ²_c
      cv::Mat rho_up(rho.rows / 2, rho.cols / 2, CV_32FC1), var_up(rho.rows / 2, rho.cols / 2, CV_32FC1);
      for (int v = 0; v < rho_up.rows; ++v)
        for (int u = 0; u < rho_up.cols; ++u) {
          float wsum = 0.0f, rsum = 0.0f;
          for (int dv = 0; dv < 2; ++dv)
            for (int du = 0; du < 2; ++du) {
              const float s2 = var.at<float>(2 * v + dv, 2 * u + du);
              if (s2 <= 0.0f) continue;
              wsum += 1.0f / s2;
              rsum += rho.at<float>(2 * v + dv, 2 * u + du) / s2;
            }
          rho_up.at<float>(v, u) = wsum > 0.0f ? rsum / wsum : 0.0f;
          var_up.at<float>(v, u) = wsum > 0.0f ? 1.0f / wsum : 0.0f;
        }
      rho = rho_up;
      var = var_up;
    }
    const EdgeLevel& level = left.levels[l];
    const LevelCamera& c = level.camera;
    std::vector<Eigen::Vector3f> pts;
    const bool subpixel = level.dt.hasLines();
    for (int v = 0; v < level.edges.rows && v < rho.rows; ++v) {
      const std::uint8_t* e = level.edges.ptr<std::uint8_t>(v);
      for (int u = 0; u < level.edges.cols && u < rho.cols; ++u) {
        if (!e[u] || var.at<float>(v, u) <= 0.0f) continue;
        const float z = 1.0f / rho.at<float>(v, u);
        double x = u, y = v;
        if (subpixel) {  // the same sub-pixel edge the current frame's point-to-line residual measures against
          Vec2 edge, n;
          level.dt.nearestLine(u, v, &edge, &n);
          const double d = (Vec2(u, v) - edge).dot(n);
          x -= d * n.x();
          y -= d * n.y();
        }
        pts.emplace_back(z * static_cast<float>((x - c.cx) / c.fx), z * static_cast<float>((y - c.cy) / c.fy), z);
      }
    }
    out.points.push_back(std::move(pts));
  }
  return out;
}

}  // namespace edgevio::vision
