#pragma once
// The distance transform of an edge map (METHOD.md §3): V(u) is the Euclidean
// distance in pixels from u to the nearest edge pixel (exact: Felzenszwalb &
// Huttenlocher 2012, which also yields that pixel), its gradient ∇V by
// central differences (evaluated at the sampled pixels only), both sampled
// bilinearly. V is the paper's residual.
//
// Given the image, it also keeps for every pixel its nearest edge as a line:
// the edge pixel refined to sub-pixel along its gradient (parabola through the
// gradient magnitude at ±1 px) and its unit normal n. The signed distance
// (u − e)·n to that line is linear near the edge, where V has a non-smooth tip
// whose central-difference gradient vanishes, and it is free of the ±0.5 px
// quantisation of Canny's edges (see AlignmentOptions::residual).
#include <opencv2/core.hpp>

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
  bool hasLines() const { return !nearest_pixel_.empty(); }
  /// Time spent building the lines [ms].
  double linesMs() const { return lines_ms_; }
  /// Nearest edge of pixel (round(u), round(v)) as a sub-pixel point and unit normal.
  void nearestLine(double u, double v, Vec2* point, Vec2* normal) const;

 private:
  void buildLines(const cv::Mat& edges, const cv::Mat& image, cv::Mat&& nearest_pixel);
  cv::Mat dist_;               // CV_32FC1
  cv::Mat nearest_pixel_;              // CV_32SC1: v·W + u of the nearest edge pixel, −1 without edges
  std::vector<int> line_of_pixel_;     // v·W + u → index into lines_ (edge pixels only)
  std::vector<Eigen::Vector4f> lines_;  // (x, y, nx, ny) per edge pixel
  double lines_ms_ = 0.0;
};

}  // namespace edgevio::vision
