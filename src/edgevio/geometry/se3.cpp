#include "edgevio/geometry/se3.h"

#include <cmath>

namespace edgevio::geometry {

namespace {
constexpr double kSmallAngle = 1e-5;

/// Barfoot's Q(ρ, φ) (eq 7.86b): the off-diagonal block of the SE(3) left Jacobian.
Mat3 jacobianQ(const Vec3& rho, const Vec3& phi) {
  const double theta2 = phi.squaredNorm();
  const double theta = std::sqrt(theta2);
  const Mat3 P = hat(phi);
  const Mat3 Rh = hat(rho);
  double c1, c2, c3;
  if (theta < kSmallAngle) {
    // Series of the three coefficients below, to order θ².
    c1 = 1.0 / 6.0 - theta2 / 120.0;
    c2 = 1.0 / 24.0 - theta2 / 720.0;
    c3 = 1.0 / 120.0 - theta2 / 2520.0;
  } else {
    const double s = std::sin(theta), c = std::cos(theta);
    c1 = (theta - s) / (theta2 * theta);
    c2 = (theta2 + 2.0 * c - 2.0) / (2.0 * theta2 * theta2);
    c3 = (2.0 * theta - 3.0 * s + theta * c) / (2.0 * theta2 * theta2 * theta);
  }
  const Mat3 PR = P * Rh;
  const Mat3 RP = Rh * P;
  const Mat3 PRP = PR * P;
  return 0.5 * Rh + c1 * (PR + RP + PRP) + c2 * (P * PR + RP * P - 3.0 * PRP) + c3 * (PRP * P + P * PRP);
}
}  // namespace

SE3 SE3::fromMatrix(const Mat4& T) { return SE3(SO3::fromMatrix(T.topLeftCorner<3, 3>()), T.topRightCorner<3, 1>()); }

SE3 SE3::exp(const Vec6& xi) {
  const Vec3 rho = xi.head<3>();
  const Vec3 phi = xi.tail<3>();
  return SE3(SO3::exp(phi), SO3::leftJacobian(phi) * rho);
}

Vec6 SE3::log() const {
  Vec6 xi;
  const Vec3 phi = R_.log();
  xi.head<3>() = SO3::leftJacobianInverse(phi) * t_;
  xi.tail<3>() = phi;
  return xi;
}

Mat4 SE3::matrix() const {
  Mat4 T = Mat4::Identity();
  T.topLeftCorner<3, 3>() = R_.matrix();
  T.topRightCorner<3, 1>() = t_;
  return T;
}

SE3 SE3::inverse() const {
  const SO3 Rinv = R_.inverse();
  return SE3(Rinv, -(Rinv * t_));
}

Mat6 SE3::adjoint() const {
  Mat6 A = Mat6::Zero();
  const Mat3 R = R_.matrix();
  A.topLeftCorner<3, 3>() = R;
  A.topRightCorner<3, 3>() = hat(t_) * R;
  A.bottomRightCorner<3, 3>() = R;
  return A;
}

Mat6 SE3::leftJacobian(const Vec6& xi) {
  // J = [[Jl(φ), Q(ρ,φ)], [0, Jl(φ)]]  (Barfoot eq 7.85)
  const Vec3 rho = xi.head<3>();
  const Vec3 phi = xi.tail<3>();
  Mat6 J = Mat6::Zero();
  const Mat3 Jl = SO3::leftJacobian(phi);
  J.topLeftCorner<3, 3>() = Jl;
  J.bottomRightCorner<3, 3>() = Jl;
  J.topRightCorner<3, 3>() = jacobianQ(rho, phi);
  return J;
}

Mat6 SE3::leftJacobianInverse(const Vec6& xi) {
  // J⁻¹ = [[Jl⁻¹, −Jl⁻¹ Q Jl⁻¹], [0, Jl⁻¹]]  (Barfoot eq 7.95)
  const Vec3 rho = xi.head<3>();
  const Vec3 phi = xi.tail<3>();
  const Mat3 Jinv = SO3::leftJacobianInverse(phi);
  Mat6 J = Mat6::Zero();
  J.topLeftCorner<3, 3>() = Jinv;
  J.bottomRightCorner<3, 3>() = Jinv;
  J.topRightCorner<3, 3>() = -Jinv * jacobianQ(rho, phi) * Jinv;
  return J;
}

SE3 interpolate(const SE3& a, const SE3& b, double t) {
  return SE3(interpolate(a.so3(), b.so3(), t), (1.0 - t) * a.translation() + t * b.translation());
}

}  // namespace edgevio::geometry
