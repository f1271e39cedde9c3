#include "edgevio/camera/camera_model.h"

#include <cmath>

namespace edgevio::camera {

bool parseDistortion(const std::string& name, Distortion* out) {
  if (name == "none") *out = Distortion::kNone;
  else if (name == "radtan" || name == "radial-tangential" || name == "plumb_bob") *out = Distortion::kRadialTangential;
  else if (name == "equidistant" || name == "fisheye") *out = Distortion::kEquidistant;
  else return false;
  return true;
}

std::string distortionName(Distortion d) {
  switch (d) {
    case Distortion::kNone: return "none";
    case Distortion::kRadialTangential: return "radial-tangential";
    case Distortion::kEquidistant: return "equidistant";
  }
  return "none";
}

Vec2 CameraModel::distort(const Vec2& x) const {
  const auto& k = coeffs;
  switch (distortion) {
    case Distortion::kNone: return x;
    case Distortion::kRadialTangential: {
      const double r2 = x.squaredNorm();
      const double radial = 1.0 + k[0] * r2 + k[1] * r2 * r2;
      const double xy = x.x() * x.y();
      return Vec2(x.x() * radial + 2.0 * k[2] * xy + k[3] * (r2 + 2.0 * x.x() * x.x()),
                  x.y() * radial + k[2] * (r2 + 2.0 * x.y() * x.y()) + 2.0 * k[3] * xy);
    }
    case Distortion::kEquidistant: {
      const double r = x.norm();
      if (r < 1e-12) return x;  // θ_d / r → 1
      const double theta = std::atan(r);
      const double t2 = theta * theta;
      const double theta_d = theta * (1.0 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
      return x * (theta_d / r);
    }
  }
  return x;
}

Vec2 CameraModel::undistort(const Vec2& xd) const {
  if (distortion == Distortion::kNone) return xd;
  // Newton on f(x) = distort(x) − xd with a central-difference Jacobian: the
  // distortion is smooth and 2-D, so this is exact to ~1e-10 and model-agnostic.
  Vec2 x = xd;
  constexpr double h = 1e-7;
  for (int it = 0; it < 20; ++it) {
    const Vec2 f = distort(x) - xd;
    if (f.norm() < 1e-13) break;
    Eigen::Matrix2d J;
    J.col(0) = (distort(x + Vec2(h, 0)) - distort(x - Vec2(h, 0))) / (2 * h);
    J.col(1) = (distort(x + Vec2(0, h)) - distort(x - Vec2(0, h))) / (2 * h);
    if (std::abs(J.determinant()) < 1e-12) break;
    x -= J.inverse() * f;
  }
  return x;
}

namespace {
double equidistantThetaD(const std::array<double, 4>& k, double theta) {
  const double t2 = theta * theta;
  return theta * (1.0 + t2 * (k[0] + t2 * (k[1] + t2 * (k[2] + t2 * k[3]))));
}
}  // namespace

Vec2 CameraModel::project(const Vec3& p_c) const {
  Vec2 xd;
  if (distortion == Distortion::kEquidistant) {
    const double r = std::hypot(p_c.x(), p_c.y());
    if (r < 1e-12 * std::abs(p_c.z())) {
      xd = Vec2(p_c.x() / p_c.z(), p_c.y() / p_c.z());  // on the axis θ_d/r → 1/Z
    } else {
      const double theta_d = equidistantThetaD(coeffs, std::atan2(r, p_c.z()));
      xd = Vec2(p_c.x(), p_c.y()) * (theta_d / r);
    }
  } else {
    xd = distort(Vec2(p_c.x() / p_c.z(), p_c.y() / p_c.z()));
  }
  return Vec2(fx * xd.x() + cx, fy * xd.y() + cy);
}

Vec3 CameraModel::unproject(const Vec2& uv) const {
  const Vec2 xd((uv.x() - cx) / fx, (uv.y() - cy) / fy);
  if (distortion == Distortion::kEquidistant) {
    // Solve θ_d(θ) = |x_d| by Newton (monotonic for real lenses), then the
    // bearing makes angle θ with the optical axis.
    const double rd = xd.norm();
    if (rd < 1e-12) return Vec3(0.0, 0.0, 1.0);
    double theta = rd;
    for (int it = 0; it < 20; ++it) {
      const double h = 1e-7;
      const double f = equidistantThetaD(coeffs, theta) - rd;
      const double df = (equidistantThetaD(coeffs, theta + h) - equidistantThetaD(coeffs, theta - h)) / (2 * h);
      if (std::abs(f) < 1e-14 || df <= 0.0) break;
      theta -= f / df;
    }
    const double s = std::sin(theta) / rd;
    return Vec3(s * xd.x(), s * xd.y(), std::cos(theta));
  }
  const Vec2 x = undistort(xd);
  return Vec3(x.x(), x.y(), 1.0).normalized();
}

std::string CameraModel::validate() const {
  if (width <= 0 || height <= 0 || width > 20000 || height > 20000) return "resolution must be positive (and sane)";
  if (!(fx > 0.0 && fy > 0.0)) return "focal lengths fx, fy must be > 0";
  if (!(std::isfinite(cx) && std::isfinite(cy))) return "principal point must be finite";
  for (double c : coeffs)
    if (!std::isfinite(c)) return "distortion coefficients must be finite";
  return {};
}

}  // namespace edgevio::camera
