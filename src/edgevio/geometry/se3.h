#pragma once
// SE(3): rigid transforms T = (R, t), acting as x ↦ R x + t.
//
// Conventions (METHOD.md §2–3):
//  - Tangent vector ξ = (ρ, φ): translation part first, rotation second, as in
//    the paper's ξ = (δp, δθ).
//  - exp(ξ) = (exp_SO3(φ), Jl(φ) ρ); perturbations on the right, T ⊞ ξ = T·exp(ξ).
//  - Naming: T_a_b maps points from frame b into frame a (T_w_b: body in world).
//  - Jacobians (Barfoot §7.1.5): exp(ξ + δ) ≈ exp(Jl(ξ) δ)·exp(ξ) ≈ exp(ξ)·exp(Jr(ξ) δ).
#include "edgevio/geometry/so3.h"

namespace edgevio::geometry {

class SE3 {
 public:
  SE3() = default;
  SE3(const SO3& R, const Vec3& t) : R_(R), t_(t) {}
  SE3(const Quat& q, const Vec3& t) : R_(q), t_(t) {}
  /// From a 4x4 homogeneous matrix; the rotation block is re-orthonormalised.
  static SE3 fromMatrix(const Mat4& T);
  static SE3 exp(const Vec6& xi);

  Vec6 log() const;
  Mat4 matrix() const;
  const SO3& so3() const { return R_; }
  const Vec3& translation() const { return t_; }
  Mat3 rotationMatrix() const { return R_.matrix(); }
  const Quat& quaternion() const { return R_.quaternion(); }

  SE3 inverse() const;
  SE3 operator*(const SE3& other) const { return SE3(R_ * other.R_, R_ * other.t_ + t_); }
  Vec3 operator*(const Vec3& p) const { return R_ * p + t_; }

  /// Adjoint: T exp(ξ) T⁻¹ = exp(Ad ξ), Ad = [[R, hat(t) R], [0, R]].
  Mat6 adjoint() const;

  static Mat6 leftJacobian(const Vec6& xi);
  static Mat6 rightJacobian(const Vec6& xi) { return leftJacobian(-xi); }
  static Mat6 leftJacobianInverse(const Vec6& xi);
  static Mat6 rightJacobianInverse(const Vec6& xi) { return leftJacobianInverse(-xi); }

 private:
  SO3 R_;
  Vec3 t_ = Vec3::Zero();
};

/// Trajectory interpolation on SO(3) x R³: rotation along the geodesic, translation
/// linearly. This is what pose lookup between two timestamps uses.
SE3 interpolate(const SE3& a, const SE3& b, double t);

}  // namespace edgevio::geometry
