#pragma once
// The one camera model: pinhole projection with radial-tangential (OpenCV
// k1,k2,p1,p2; EuRoC "radial-tangential", Kalibr "radtan") or equidistant
// (Kannala-Brandt k1..k4; Kalibr "equidistant", OpenCV fisheye) distortion.
//
//   u = fx·x_d + cx,  v = fy·y_d + cy,  (x_d, y_d) = d(X/Z, Y/Z)
//   radtan:      x_d = x(1 + k1 r² + k2 r⁴) + 2p1 xy + p2(r² + 2x²),
//                y_d = y(1 + k1 r² + k2 r⁴) + p1(r² + 2y²) + 2p2 xy
//   equidistant: θ = atan(r), θ_d = θ(1 + k1θ² + k2θ⁴ + k3θ⁶ + k4θ⁸), x_d = (θ_d / r) x
#include <array>
#include <string>

#include "edgevio/geometry/types.h"

namespace edgevio::camera {

enum class Distortion { kNone, kRadialTangential, kEquidistant };

/// "none", "radtan"/"radial-tangential", "equidistant"/"fisheye"; false if unknown.
bool parseDistortion(const std::string& name, Distortion* out);
std::string distortionName(Distortion d);

struct CameraModel {
  int width = 0;   ///< image width [px]
  int height = 0;  ///< image height [px]
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0;  ///< intrinsics [px]
  Distortion distortion = Distortion::kNone;
  std::array<double, 4> coeffs{};  ///< k1,k2,p1,p2 (radtan) or k1..k4 (equidistant)

  /// Normalised undistorted (x, y) → normalised distorted coordinates.
  Vec2 distort(const Vec2& x) const;
  /// Inverse of distort by Newton's method (converges in a few steps inside the image).
  Vec2 undistort(const Vec2& xd) const;
  /// Camera-frame point → pixel. Radial-tangential and none need Z > 0;
  /// equidistant uses θ = atan2(√(X²+Y²), Z) and so also covers rays beyond 90°.
  Vec2 project(const Vec3& p_c) const;
  /// Pixel → unit-length bearing vector of the viewing ray.
  Vec3 unproject(const Vec2& uv) const;
  bool inImage(const Vec2& uv, double border = 0.0) const {
    return uv.x() >= border && uv.y() >= border && uv.x() <= width - 1 - border && uv.y() <= height - 1 - border;
  }
  /// Empty when valid, else what is wrong.
  std::string validate() const;
};

}  // namespace edgevio::camera
