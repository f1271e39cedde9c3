#pragma once
// The distance transform of an edge map (METHOD.md §3): V(u) is the Euclidean
// distance in pixels from u to the nearest edge pixel (exact: Felzenszwalb &
// Huttenlocher 2012, which also yields that pixel), its gradient ∇V by
// central differences (evaluated at the sampled pixels only), both sampled
// bilinearly. V is the paper's residual.
//
// Given the image, it also keeps for every pixel its nearest edge as a line:
// the edge pixel refined to sub-pixel along its gradient (the maximum along n
// of a quadratic fitted to the gradient magnitude's 3x3 neighbourhood) and its
// unit normal n. The signed distance
// (u − e)·n to that line is linear near the edge, where V has a non-smooth tip
// whose central-difference gradient vanishes, and it is free of the ±0.5 px
// quantisation of Canny's edges (see AlignmentOptions::residual).
#include <opencv2/core.hpp>

#include <algorithm>
#include <vector>

#include "edgevio/geometry/types.h"

namespace edgevio::vision {

class DistanceTransform {
 public:
  DistanceTransform() = default;
  /// `edges`: CV_8UC1, non-zero on edge pixels. With `image` (the grey image
  /// the edges came from) the nearest-edge lines are built too.
  explicit DistanceTransform(const cv::Mat& edges, const cv::Mat& image = cv::Mat());

  int width() const { return dist_.cols; }
  int height() const { return dist_.rows; }
  /// V and ∇V at a sub-pixel location; the caller keeps u within [0, W−2]x[0, H−2].
  float value(double u, double v) const;
  void valueAndGradient(double u, double v, float* value, float* du, float* dv) const;
  const cv::Mat& distance() const { return dist_; }
  bool hasLines() const { return !nearest_line_.empty(); }
  /// Time spent building the lines [ms].
  double linesMs() const { return lines_ms_; }
  /// Nearest edge of pixel (round(u), round(v)) as a sub-pixel point and unit normal.
  void nearestLine(double u, double v, Vec2* point, Vec2* normal) const;

 private:
  void buildLines(const cv::Mat& edges, const cv::Mat& image, cv::Mat&& nearest_pixel);
  cv::Mat dist_;               // CV_32FC1
  cv::Mat nearest_line_;                // CV_32SC1: index into lines_ of the nearest edge pixel, −1 without edges
  std::vector<Eigen::Vector4f> lines_;  // (x, y, nx, ny) per edge pixel
  double lines_ms_ = 0.0;
};

// Defined here: the alignment calls them for every point of every iteration.

inline void DistanceTransform::nearestLine(double u, double v, Vec2* point, Vec2* normal) const {
  const int x = std::clamp(static_cast<int>(u + 0.5), 0, nearest_line_.cols - 1);
  const int y = std::clamp(static_cast<int>(v + 0.5), 0, nearest_line_.rows - 1);
  const int i = nearest_line_.at<int>(y, x);
  if (i < 0) {  // no edge at all in the image
    *point = Vec2(u, v);
    *normal = Vec2(1.0, 0.0);
    return;
  }
  const Eigen::Vector4f& l = lines_[static_cast<std::size_t>(i)];
  *point = Vec2(l[0], l[1]);
  *normal = Vec2(l[2], l[3]);
}

inline float DistanceTransform::value(double u, double v) const {
  const int u0 = static_cast<int>(u), v0 = static_cast<int>(v);
  const float a = static_cast<float>(u - u0), b = static_cast<float>(v - v0);
  const float* r0 = dist_.ptr<float>(v0);
  const float* r1 = dist_.ptr<float>(v0 + 1);
  return (1 - b) * ((1 - a) * r0[u0] + a * r0[u0 + 1]) + b * ((1 - a) * r1[u0] + a * r1[u0 + 1]);
}

inline void DistanceTransform::valueAndGradient(double u, double v, float* value, float* du, float* dv) const {
  // ∇V by central differences at the four surrounding pixels, computed here
  // from V (a 4x4 neighbourhood) instead of stored maps: building the maps
  // cost 46 % of the transform for every pixel of every level, every frame,
  // while only the sampled pixels need them.
  const int W = dist_.cols, H = dist_.rows;
  const int u0 = static_cast<int>(u), v0 = static_cast<int>(v);
  const float a = static_cast<float>(u - u0), b = static_cast<float>(v - v0);
  const auto lerp2 = [&](float f00, float f10, float f01, float f11) {
    return (1 - b) * ((1 - a) * f00 + a * f10) + b * ((1 - a) * f01 + a * f11);
  };
  if (u0 >= 1 && v0 >= 1 && u0 <= W - 3 && v0 <= H - 3) {
    // Inside: the 4x4 neighbourhood needs no clamping (the same sums as below).
    const float* r[4] = {dist_.ptr<float>(v0 - 1), dist_.ptr<float>(v0), dist_.ptr<float>(v0 + 1), dist_.ptr<float>(v0 + 2)};
    const auto gu = [&](int x, int y) { return (r[y][x + 1] - r[y][x - 1]) / 2.0f; };
    const auto gv = [&](int x, int y) { return (r[y + 1][x] - r[y - 1][x]) / 2.0f; };
    *value = lerp2(r[1][u0], r[1][u0 + 1], r[2][u0], r[2][u0 + 1]);
    *du = lerp2(gu(u0, 1), gu(u0 + 1, 1), gu(u0, 2), gu(u0 + 1, 2));
    *dv = lerp2(gv(u0, 1), gv(u0 + 1, 1), gv(u0, 2), gv(u0 + 1, 2));
    return;
  }
  const auto at = [&](int x, int y) { return dist_.at<float>(std::clamp(y, 0, H - 1), std::clamp(x, 0, W - 1)); };
  const auto gu = [&](int x, int y) {
    const int xl = std::max(x - 1, 0), xr = std::min(x + 1, W - 1);
    return (at(xr, y) - at(xl, y)) / static_cast<float>(xr - xl);
  };
  const auto gv = [&](int x, int y) {
    const int yu = std::max(y - 1, 0), yd = std::min(y + 1, H - 1);
    return (at(x, yd) - at(x, yu)) / static_cast<float>(yd - yu);
  };
  *value = lerp2(at(u0, v0), at(u0 + 1, v0), at(u0, v0 + 1), at(u0 + 1, v0 + 1));
  *du = lerp2(gu(u0, v0), gu(u0 + 1, v0), gu(u0, v0 + 1), gu(u0 + 1, v0 + 1));
  *dv = lerp2(gv(u0, v0), gv(u0 + 1, v0), gv(u0, v0 + 1), gv(u0 + 1, v0 + 1));
}

}  // namespace edgevio::vision
