#include "edgevio/camera/stereo_rectifier.h"

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "edgevio/common/error.h"

namespace edgevio::camera {

namespace {
cv::Mat intrinsicMatrix(const CameraModel& c) {
  return (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
}
cv::Mat distortionVector(const CameraModel& c) {
  if (c.distortion == Distortion::kNone) return cv::Mat::zeros(4, 1, CV_64F);
  return (cv::Mat_<double>(4, 1) << c.coeffs[0], c.coeffs[1], c.coeffs[2], c.coeffs[3]);
}
Mat3 toEigen3(const cv::Mat& m) {
  Mat3 r;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) r(i, j) = m.at<double>(i, j);
  return r;
}
}  // namespace

StereoRectifier::StereoRectifier(const StereoRig& rig, const RectificationOptions& options) : rig_(rig) {
  const CameraModel& c0 = rig.cam[0];
  const CameraModel& c1 = rig.cam[1];
  if (c0.width != c1.width || c0.height != c1.height)
    throw InputError("stereo rectification: both cameras must have the same resolution");
  if (c0.distortion == Distortion::kEquidistant && c1.distortion != Distortion::kEquidistant)
    throw InputError("stereo rectification: both cameras must use the same distortion model");

  // stereoRectify wants the pose of camera 0 expressed in camera 1: x1 = R x0 + T.
  const geometry::SE3 T_c1_c0 = rig.T_c0_c1().inverse();
  cv::Mat R(3, 3, CV_64F), T(3, 1, CV_64F);
  const Mat3 Re = T_c1_c0.rotationMatrix();
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) R.at<double>(i, j) = Re(i, j);
    T.at<double>(i) = T_c1_c0.translation()(i);
  }
  const cv::Size size(c0.width, c0.height);
  cv::Mat R0, R1, P0, P1, Q;
  const cv::Mat K0 = intrinsicMatrix(c0), K1 = intrinsicMatrix(c1);
  const cv::Mat D0 = distortionVector(c0), D1 = distortionVector(c1);
  if (c0.distortion == Distortion::kEquidistant) {
    cv::fisheye::stereoRectify(K0, D0, K1, D1, size, R, T, R0, R1, P0, P1, Q, cv::CALIB_ZERO_DISPARITY, size,
                               options.alpha);
    cv::fisheye::initUndistortRectifyMap(K0, D0, R0, P0, size, CV_16SC2, map_x_[0], map_y_[0]);
    cv::fisheye::initUndistortRectifyMap(K1, D1, R1, P1, size, CV_16SC2, map_x_[1], map_y_[1]);
  } else {
    cv::stereoRectify(K0, D0, K1, D1, size, R, T, R0, R1, P0, P1, Q, cv::CALIB_ZERO_DISPARITY, options.alpha, size);
    cv::initUndistortRectifyMap(K0, D0, R0, P0, size, CV_16SC2, map_x_[0], map_y_[0]);
    cv::initUndistortRectifyMap(K1, D1, R1, P1, size, CV_16SC2, map_x_[1], map_y_[1]);
  }
  rectified_.width = c0.width;
  rectified_.height = c0.height;
  rectified_.fx = P0.at<double>(0, 0);
  rectified_.fy = P0.at<double>(1, 1);
  rectified_.cx = P0.at<double>(0, 2);
  rectified_.cy = P0.at<double>(1, 2);
  rectified_.distortion = Distortion::kNone;
  // P1(0,3) = −f·b for a horizontal rig.
  baseline_ = std::abs(P1.at<double>(0, 3) / P1.at<double>(0, 0));
  R_rect_raw_[0] = toEigen3(R0);
  R_rect_raw_[1] = toEigen3(R1);
  for (int i = 0; i < 2; ++i)
    T_b_rect_[i] = rig.T_b_c[i] * geometry::SE3(geometry::SO3::fromMatrix(R_rect_raw_[i].transpose()), Vec3::Zero());
}

void StereoRectifier::rectify(const cv::Mat& left_raw, const cv::Mat& right_raw, cv::Mat* left, cv::Mat* right) const {
  *left = rectify(0, left_raw);
  *right = rectify(1, right_raw);
}

cv::Mat StereoRectifier::rectify(int i, const cv::Mat& raw) const {
  cv::Mat out;
  cv::remap(raw, out, map_x_[i], map_y_[i], cv::INTER_LINEAR, cv::BORDER_CONSTANT);
  return out;
}

Vec2 StereoRectifier::rectifyPoint(int i, const Vec2& raw_uv) const {
  const Vec3 ray = R_rect_raw_[i] * rig_.cam[i].unproject(raw_uv);
  return rectified_.project(ray);
}

}  // namespace edgevio::camera
