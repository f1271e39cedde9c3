// The camera model against OpenCV's projection functions (an independent
// implementation of the same formulas) and its own inverse.
#include "edgevio/camera/camera_model.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

namespace edgevio::camera {
namespace {

CameraModel pinhole(int width, int height, double fx, double fy, double cx, double cy, Distortion d, const std::array<double, 4>& coeffs) {
  CameraModel c;
  c.width = width;
  c.height = height;
  c.fx = fx;
  c.fy = fy;
  c.cx = cx;
  c.cy = cy;
  c.distortion = d;
  c.coeffs = coeffs;
  return c;
}

CameraModel eurocCam0() {
  return pinhole(752, 480, 458.654, 457.296, 367.215, 248.375, Distortion::kRadialTangential,
                 {-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05});
}

CameraModel tumViCam0() {  // TUM-VI 512x512 equidistant calibration
  return pinhole(512, 512, 190.978, 190.973, 254.932, 256.897, Distortion::kEquidistant,
                 {0.0034823, 0.000715034, -0.00205341, 0.000202937});
}

std::vector<Vec3> testPoints() {
  std::vector<Vec3> p;
  for (double x = -1.5; x <= 1.5; x += 0.5)
    for (double y = -1.0; y <= 1.0; y += 0.5) p.emplace_back(x, y, 2.0);
  return p;
}

/// OpenCV's projection of points at the identity pose with intrinsics K and distortion D.
using OpenCvProjection = void (*)(const std::vector<cv::Point3d>&, const cv::Mat& K, const cv::Mat& D, std::vector<cv::Point2d>*);

/// c.project agrees with OpenCV's projection to 1e-9 px on the test points.
void expectProjectsAsOpenCv(const CameraModel& c, OpenCvProjection project) {
  const cv::Mat K = (cv::Mat_<double>(3, 3) << c.fx, 0, c.cx, 0, c.fy, c.cy, 0, 0, 1);
  const cv::Mat D = (cv::Mat_<double>(4, 1) << c.coeffs[0], c.coeffs[1], c.coeffs[2], c.coeffs[3]);
  for (const Vec3& p : testPoints()) {
    std::vector<cv::Point2d> out;
    project({{p.x(), p.y(), p.z()}}, K, D, &out);
    EXPECT_LT((c.project(p) - Vec2(out[0].x, out[0].y)).norm(), 1e-9);
  }
}

TEST(CameraModel, RadTanMatchesOpenCv) {
  expectProjectsAsOpenCv(eurocCam0(), [](const std::vector<cv::Point3d>& in, const cv::Mat& K, const cv::Mat& D,
                                         std::vector<cv::Point2d>* out) {
    cv::projectPoints(in, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D, *out);
  });
}

TEST(CameraModel, EquidistantMatchesOpenCvFisheye) {
  expectProjectsAsOpenCv(tumViCam0(), [](const std::vector<cv::Point3d>& in, const cv::Mat& K, const cv::Mat& D,
                                         std::vector<cv::Point2d>* out) {
    cv::fisheye::projectPoints(in, *out, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D);
  });
}

TEST(CameraModel, UnprojectInvertsProjectOverTheImage) {
  for (const CameraModel& c : {eurocCam0(), tumViCam0()}) {
    for (int v = 0; v < c.height; v += 31) {
      for (int u = 0; u < c.width; u += 37) {
        const Vec2 uv(u, v);
        const Vec3 ray = c.unproject(uv);
        EXPECT_NEAR(ray.norm(), 1.0, 1e-12);
        // Round trip to 1e-6 px, far below anything the front end resolves.
        EXPECT_LT((c.project(3.0 * ray) - uv).norm(), 1e-6) << distortionName(c.distortion) << " " << u << "," << v;
      }
    }
  }
}

TEST(CameraModel, NoDistortionIsPinhole) {
  CameraModel c = eurocCam0();
  c.distortion = Distortion::kNone;
  const Vec2 uv = c.project(Vec3(0.5, -0.25, 2.0));
  EXPECT_NEAR(uv.x(), c.fx * 0.25 + c.cx, 1e-12);
  EXPECT_NEAR(uv.y(), c.fy * -0.125 + c.cy, 1e-12);
}

TEST(CameraModel, ValidateAndNames) {
  CameraModel c = eurocCam0();
  EXPECT_TRUE(c.validate().empty());
  c.fx = 0.0;
  EXPECT_FALSE(c.validate().empty());
  Distortion d;
  EXPECT_TRUE(parseDistortion("radtan", &d));
  EXPECT_EQ(d, Distortion::kRadialTangential);
  EXPECT_TRUE(parseDistortion("equidistant", &d));
  EXPECT_FALSE(parseDistortion("double-sphere", &d));
}

}  // namespace
}  // namespace edgevio::camera
