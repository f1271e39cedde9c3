#pragma once
// Stereo rectification (METHOD.md §3): both images are warped to a common
// pinhole camera whose rows are epipolar lines (zero disparity at infinity,
// free scaling alpha, default 0). The remap tables are computed once.
#include <opencv2/core.hpp>

#include "edgevio/camera/calibration.h"
#include "edgevio/camera/rectification_options.h"

namespace edgevio::camera {

class StereoRectifier {
 public:
  StereoRectifier(const StereoRig& rig, const RectificationOptions& options);

  /// Rectifies a raw 8-bit pair (sizes must match the calibration).
  void rectify(const cv::Mat& left_raw, const cv::Mat& right_raw, cv::Mat* left, cv::Mat* right) const;
  /// Rectifies the raw 8-bit image of camera i (0 left, 1 right).
  cv::Mat rectify(int i, const cv::Mat& raw) const;

  /// Raw camera i as calibrated.
  const CameraModel& rawCamera(int i) const { return rig_.cam[i]; }
  /// The rectified camera shared by both images (no distortion).
  const CameraModel& rectifiedCamera() const { return rectified_; }
  /// Distance between the two rectified optical centres [m]; disparity d gives depth f·b/d.
  double baseline() const { return baseline_; }
  /// Pose of rectified camera i in the body frame.
  const geometry::SE3& T_b_rect(int i) const { return T_b_rect_[i]; }
  /// Maps a raw pixel of camera i to the rectified image.
  Vec2 rectifyPoint(int i, const Vec2& raw_uv) const;

 private:
  StereoRig rig_;
  CameraModel rectified_;
  double baseline_ = 0.0;
  geometry::SE3 T_b_rect_[2];
  // Fixed-point tables (CV_16SC2 integer pixel + CV_16UC1 1/32-pixel
  // interpolation index): remap runs about twice as fast as with float tables.
  cv::Mat map_x_[2], map_y_[2];
  Mat3 R_rect_raw_[2];  // rotation from raw camera i to rectified camera i
};

}  // namespace edgevio::camera
