#include "edgevio/geometry/so3.h"

#include <cmath>

namespace edgevio::geometry {

namespace {
// Below this angle the closed forms lose precision and Taylor series are used;
// every series is truncated after a term of order θ², so its error is O(θ⁴) ≈ 1e-20.
constexpr double kSmallAngle = 1e-5;
}  // namespace

Mat3 hat(const Vec3& a) {
  Mat3 m;
  m << 0.0, -a.z(), a.y(),  //
      a.z(), 0.0, -a.x(),   //
      -a.y(), a.x(), 0.0;
  return m;
}

Vec3 vee(const Mat3& m) { return Vec3(m(2, 1) - m(1, 2), m(0, 2) - m(2, 0), m(1, 0) - m(0, 1)) * 0.5; }

SO3::SO3(const Quat& q) : q_(q.normalized()) {}

SO3::SO3(const Quat& q, Renormalise) : q_(q) {
  // A product of unit quaternions drifts from unit norm by O(ε) per product;
  // renormalising here keeps the class invariant over long chains.
  q_.normalize();
}

SO3 SO3::fromMatrix(const Mat3& R) {
  // Eigen's quaternion-from-matrix (Shepperd's method) is stable for any angle;
  // for a non-orthonormal input it yields a nearby rotation after normalisation.
  return SO3(Quat(R));
}

SO3 SO3::exp(const Vec3& phi) {
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  double imag_factor;  // sin(θ/2)/θ
  double real;
  if (theta < kSmallAngle) {
    imag_factor = 0.5 - theta2 / 48.0;
    real = 1.0 - theta2 / 8.0;
  } else {
    imag_factor = std::sin(0.5 * theta) / theta;
    real = std::cos(0.5 * theta);
  }
  return SO3(Quat(real, imag_factor * phi.x(), imag_factor * phi.y(), imag_factor * phi.z()));
}

Vec3 SO3::log() const {
  // q and -q are the same rotation; choose w >= 0 so that θ = 2·atan2(|v|, w) ∈ [0, π].
  const double sign = q_.w() < 0.0 ? -1.0 : 1.0;
  const double w = sign * q_.w();
  const Vec3 v = sign * q_.vec();
  const double n = v.norm();
  double factor;  // θ / |v|
  if (n < kSmallAngle) {
    // θ = 2 atan(n/w) = 2(n/w − n³/(3w³) + …)
    factor = 2.0 / w - 2.0 * n * n / (3.0 * w * w * w);
  } else {
    // atan2 rather than acos(w): accurate near both 0 and π.
    factor = 2.0 * std::atan2(n, w) / n;
  }
  return factor * v;
}

Mat3 SO3::leftJacobian(const Vec3& phi) {
  // Jl(φ) = I + (1−cosθ)/θ² Φ + (θ−sinθ)/θ³ Φ²,  Φ = hat(φ)  (Barfoot eq 7.77a)
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  const Mat3 Phi = hat(phi);
  double a, b;
  if (theta < kSmallAngle) {
    a = 0.5 - theta2 / 24.0;
    b = 1.0 / 6.0 - theta2 / 120.0;
  } else {
    a = (1.0 - std::cos(theta)) / theta2;
    b = (theta - std::sin(theta)) / (theta2 * theta);
  }
  return Mat3::Identity() + a * Phi + b * Phi * Phi;
}

Mat3 SO3::leftJacobianInverse(const Vec3& phi) {
  // Jl⁻¹(φ) = I − ½Φ + (1/θ² − cot(θ/2)/(2θ)) Φ²   (Barfoot eq 7.77b, with
  // (1+cosθ)/sinθ = cot(θ/2), which stays finite at θ = π).
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  const Mat3 Phi = hat(phi);
  double c;
  if (theta < kSmallAngle) {
    c = 1.0 / 12.0 + theta2 / 720.0;
  } else {
    c = 1.0 / theta2 - 0.5 / (theta * std::tan(0.5 * theta));
  }
  return Mat3::Identity() - 0.5 * Phi + c * Phi * Phi;
}

SO3 interpolate(const SO3& a, const SO3& b, double t) { return a * SO3::exp(t * (a.inverse() * b).log()); }

double angle(const SO3& R) { return R.log().norm(); }

Quat quaternionFromWxyz(double w, double x, double y, double z) { return Quat(w, x, y, z); }
Quat quaternionFromXyzw(double x, double y, double z, double w) { return Quat(w, x, y, z); }

}  // namespace edgevio::geometry
