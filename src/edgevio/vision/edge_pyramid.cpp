#include "edgevio/vision/edge_pyramid.h"

#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <chrono>

namespace edgevio::vision {

LevelCamera LevelCamera::half() const {
  return {fx / 2, fy / 2, (cx + 0.5) / 2 - 0.5, (cy + 0.5) / 2 - 0.5, width / 2, height / 2};
}

cv::Mat downsample2(const cv::Mat& image) {
  const int W = image.cols / 2, H = image.rows / 2;  // locals: a store to `o` cannot change them, so the loop vectorises
  cv::Mat out(H, W, CV_8UC1);
  for (int v = 0; v < H; ++v) {
    const std::uint8_t* a = image.ptr<std::uint8_t>(2 * v);
    const std::uint8_t* b = image.ptr<std::uint8_t>(2 * v + 1);
    std::uint8_t* o = out.ptr<std::uint8_t>(v);
    for (int u = 0; u < W; ++u)
      o[u] = static_cast<std::uint8_t>((a[2 * u] + a[2 * u + 1] + b[2 * u] + b[2 * u + 1] + 2) / 4);
  }
  return out;
}

std::pair<double, double> cannyThresholds(const cv::Mat& image, const VisionOptions& o) {
  if (o.canny_thresholds == CannyThresholds::kFixed) return {o.canny_fixed_low, o.canny_fixed_high};
  cv::Mat unused;
  const double t = cv::threshold(image, unused, 0, 255, cv::THRESH_BINARY | cv::THRESH_OTSU);
  const double low = std::clamp(t - o.canny_otsu_offset, o.canny_min_low, o.canny_max_high - 1.0);
  const double high = std::clamp(t + o.canny_otsu_offset, low + 1.0, o.canny_max_high);
  return {low, high};
}

EdgePyramid buildEdgePyramid(const cv::Mat& rectified_full, const camera::CameraModel& cam, const VisionOptions& o,
                             bool with_distance_transform) {
  using Clock = std::chrono::steady_clock;
  EdgePyramid p;
  p.full = rectified_full;
  LevelCamera lc{cam.fx, cam.fy, cam.cx, cam.cy, cam.width, cam.height};
  cv::Mat img = rectified_full;
  for (int l = 0; l < o.levels; ++l) {
    img = downsample2(img);
    lc = lc.half();
    EdgeLevel level;
    level.camera = lc;
    level.image = img;
    const auto t0 = Clock::now();
    const auto [low, high] = cannyThresholds(img, o);
    cv::Canny(img, level.edges, low, high, 3, true);
    level.edge_count = cv::countNonZero(level.edges);
    const auto t1 = Clock::now();
    // Edge lines serve the point-to-line residual, used on level 0 only.
    if (with_distance_transform) level.dt = l == 0 ? DistanceTransform(level.edges, img) : DistanceTransform(level.edges);
    const auto t2 = Clock::now();
    if (with_distance_transform && l == 0) p.lines_ms = level.dt.linesMs();
    p.canny_ms += std::chrono::duration<double, std::milli>(t1 - t0).count();
    p.dt_ms += std::chrono::duration<double, std::milli>(t2 - t1).count();
    p.levels.push_back(std::move(level));
  }
  return p;
}

}  // namespace edgevio::vision
