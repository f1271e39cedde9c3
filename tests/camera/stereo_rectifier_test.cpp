// Rectification puts corresponding points on the same row, with the disparity
// f·b/Z of a pinhole stereo pair.
#include "edgevio/camera/stereo_rectifier.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include "common/mini_dataset.h"
#include "edgevio/io/calibration_io.h"

namespace edgevio::camera {
namespace {

StereoRig eurocRig() {
  test::TempDir dir;
  const std::string root = test::writeMiniDataset(dir, {1, 752, 480});
  return io::loadCalibration(root);
}

TEST(StereoRectifier, EpipolarRowsAndDisparity) {
  const StereoRig rig = eurocRig();
  const StereoRectifier rect(rig, RectificationOptions{});
  const CameraModel& K = rect.rectifiedCamera();
  EXPECT_NEAR(rect.baseline(), 0.1101, 0.0005);
  const geometry::SE3 T_c0_c1 = rig.T_c0_c1();
  const geometry::SE3 T_r0_c0 = rect.T_b_rect(0).inverse() * rig.T_b_c[0];
  int tested = 0;
  for (double x = -1.0; x <= 1.0; x += 0.25) {
    for (double y = -0.6; y <= 0.6; y += 0.3) {
      for (double z : {1.0, 2.5, 6.0}) {
        const Vec3 p0(x * z / 2, y * z / 2, z);  // point in raw cam0
        const Vec3 p1 = T_c0_c1.inverse() * p0;
        const Vec2 raw0 = rig.cam[0].project(p0), raw1 = rig.cam[1].project(p1);
        if (!rig.cam[0].inImage(raw0, 5) || !rig.cam[1].inImage(raw1, 5)) continue;
        const Vec2 r0 = rect.rectifyPoint(0, raw0), r1 = rect.rectifyPoint(1, raw1);
        EXPECT_NEAR(r0.y(), r1.y(), 1e-6);
        const double depth = (T_r0_c0 * p0).z();
        EXPECT_NEAR(r0.x() - r1.x(), K.fx * rect.baseline() / depth, 1e-6);
        ++tested;
      }
    }
  }
  EXPECT_GT(tested, 50);
}

TEST(StereoRectifier, RemapAgreesWithPointMapping) {
  const StereoRig rig = eurocRig();
  const StereoRectifier rect(rig, RectificationOptions{});
  // A single bright dot in the raw left image lands where rectifyPoint says.
  cv::Mat raw = cv::Mat::zeros(480, 752, CV_8UC1), dummy = raw.clone();
  const Vec2 raw_uv(500.0, 300.0);
  cv::circle(raw, cv::Point(500, 300), 2, cv::Scalar(255), cv::FILLED);
  cv::Mat left, right;
  rect.rectify(raw, dummy, &left, &right);
  const cv::Moments m = cv::moments(left, false);
  ASSERT_GT(m.m00, 0.0);
  const Vec2 centroid(m.m10 / m.m00, m.m01 / m.m00);
  EXPECT_LT((centroid - rect.rectifyPoint(0, raw_uv)).norm(), 0.3);
}

}  // namespace
}  // namespace edgevio::camera
