#pragma once
// Per-frame image processing of the front end (METHOD.md §3, pre-processing):
// the rectified left image, downsampled once (752x480 → 376x240 = level 0),
// a pyramid by 2x2 averaging, Canny edges on every level, and the distance
// transform of every level's edge map.
#include <opencv2/core.hpp>

#include <vector>

#include "edgevio/camera/camera_model.h"
#include "edgevio/vision/distance_transform.h"
#include "edgevio/vision/vision_options.h"

namespace edgevio::vision {

/// Pinhole intrinsics of one pyramid level.
struct LevelCamera {
  double fx, fy, cx, cy;
  int width, height;
  /// Level l+1 from level l: f' = f/2, c' = (c + 0.5)/2 − 0.5 (pixel centres stay aligned).
  LevelCamera half() const;
};

struct EdgeLevel {
  LevelCamera camera;
  cv::Mat image;      ///< CV_8UC1
  cv::Mat edges;      ///< CV_8UC1, 255 on edge pixels
  int edge_count = 0;
  DistanceTransform dt;
};

struct EdgePyramid {
  cv::Mat full;  ///< the rectified image the pyramid was built from (keyframes match stereo on it)
  std::vector<EdgeLevel> levels;
  double canny_ms = 0.0, dt_ms = 0.0;  ///< time spent, for frames.csv and benchmarks
  double lines_ms = 0.0;               ///< of which: sub-pixel edge lines on level 0 (not in the paper)
};

/// 2x2 block average (odd trailing rows/columns dropped).
cv::Mat downsample2(const cv::Mat& image);

/// Canny thresholds for an image: (t − offset, t + offset) from its Otsu threshold, clamped.
std::pair<double, double> cannyThresholds(const cv::Mat& image, const VisionOptions& options);

/// Builds the pyramid from a rectified full-resolution left image and the
/// rectified camera (level 0 is half its resolution).
EdgePyramid buildEdgePyramid(const cv::Mat& rectified_full, const camera::CameraModel& rectified_camera,
                             const VisionOptions& options, bool with_distance_transform = true);

}  // namespace edgevio::vision
