#pragma once
// SO(3): 3-D rotations, stored as a unit Hamilton quaternion.
//
// Conventions (METHOD.md §2, used by every module):
//  - exp/log map between a rotation vector phi in R^3 and a rotation.
//  - Perturbations are on the right: R ⊞ δ = R · exp(δ) (paper eq 9).
//  - Invariant: |q| = 1 to within 1e-9; every constructor normalises.
//  - Jacobians (Barfoot, "State Estimation for Robotics", §7.1.3):
//      exp(phi + δ) ≈ exp(Jl(phi) δ) · exp(phi) ≈ exp(phi) · exp(Jr(phi) δ).
#include "edgevio/geometry/types.h"

namespace edgevio::geometry {

/// Skew-symmetric matrix: hat(a) b = a × b.
Mat3 hat(const Vec3& a);
/// Inverse of hat for a skew-symmetric matrix.
Vec3 vee(const Mat3& m);

class SO3 {
 public:
  SO3() = default;
  /// From any non-zero quaternion; it is normalised.
  explicit SO3(const Quat& q);
  /// From a rotation matrix (projected to the nearest rotation via a quaternion).
  static SO3 fromMatrix(const Mat3& R);
  /// exp: rotation vector -> rotation. Exact at any angle, Taylor-expanded near 0.
  static SO3 exp(const Vec3& phi);

  /// log: rotation -> rotation vector with angle in [0, π].
  Vec3 log() const;
  Mat3 matrix() const { return q_.toRotationMatrix(); }
  const Quat& quaternion() const { return q_; }
  SO3 inverse() const { return SO3(q_.conjugate(), Normalised{}); }
  /// Adjoint: R exp(δ) R⁻¹ = exp(Ad δ), Ad = R.
  Mat3 adjoint() const { return matrix(); }

  SO3 operator*(const SO3& other) const { return SO3(q_ * other.q_, Renormalise{}); }
  Vec3 operator*(const Vec3& v) const { return q_ * v; }

  /// Left and right Jacobians of exp and their inverses (see header comment).
  static Mat3 leftJacobian(const Vec3& phi);
  static Mat3 rightJacobian(const Vec3& phi) { return leftJacobian(-phi); }
  static Mat3 leftJacobianInverse(const Vec3& phi);
  static Mat3 rightJacobianInverse(const Vec3& phi) { return leftJacobianInverse(-phi); }

 private:
  struct Normalised {};
  struct Renormalise {};
  SO3(const Quat& q, Normalised) : q_(q) {}
  SO3(const Quat& q, Renormalise);
  Quat q_ = Quat::Identity();
};

/// Geodesic interpolation: a · exp(t · log(a⁻¹ b)), t in [0, 1].
SO3 interpolate(const SO3& a, const SO3& b, double t);

/// Angle of a rotation in radians, in [0, π].
double angle(const SO3& R);

/// Quaternion from four numbers in the order the file formats use.
Quat quaternionFromWxyz(double w, double x, double y, double z);
Quat quaternionFromXyzw(double x, double y, double z, double w);

}  // namespace edgevio::geometry
