#pragma once
// The links of the sliding window (METHOD.md §5) as residual functions of the
// states they join. States are imu::NavState, perturbed on the right:
// R ← R·Exp(δθ), p ← p + δp, v ← v + δv, b ← b + δb, error order
// [δp, δθ, δv, δb_a, δb_g] (imu::Block).
#include "edgevio/geometry/se3.h"
#include "edgevio/imu/preintegration.h"

namespace edgevio::estimator {

using Mat6x15 = Eigen::Matrix<double, 6, 15>;

/// A tracking (or loop-closure) link (eq 19): the measured relative pose
/// T_nr of camera n relative to camera r (maps points from r's camera frame
/// into n's), with the alignment's information matrix (inverse covariance).
struct RelativePoseLink {
  geometry::SE3 T_nr;
  Mat6 information = Mat6::Identity();
};

/// T_nr of two states' cameras as the states predict it:
/// (T_w_bn T_b_c)⁻¹ (T_w_br T_b_c) = T_c_b X_n⁻¹ X_r T_b_c.
geometry::SE3 predictedRelativePose(const imu::NavState& r, const imu::NavState& n, const geometry::SE3& T_b_c);

/// r = Log(T_meas⁻¹ · T_pred), T_pred = predictedRelativePose(r, n, T_b_c), and its
/// Jacobians with respect to the 15-dimensional errors of states r and n.
/// Derivation: with A = T_c_b, T_pred = A X_n⁻¹ X_r A⁻¹; X_r·Exp(ξ) gives
/// T_pred·Exp(Ad_A ξ) and X_n·Exp(ξ) gives T_pred·Exp(−Ad_{T_pred⁻¹} Ad_A ξ), so
/// ∂r/∂ξ_r = Jr⁻¹(r) Ad_A and ∂r/∂ξ_n = −Jr⁻¹(r) Ad_{T_pred⁻¹} Ad_A; a state's
/// (δp, δθ) is the twist (Rᵀδp, δθ). The extrinsics perturbed on the right,
/// T_b_c·Exp(ζ), make A = Exp(−ζ)·A and T_pred = Exp(−ζ)·T_pred·Exp(ζ) =
/// T_pred·Exp((I − Ad_{T_pred⁻¹}) ζ): ∂r/∂ζ = Jr⁻¹(r)(I − Ad_{T_pred⁻¹}).
Vec6 relativePoseResidual(const geometry::SE3& T_nr_measured, const imu::NavState& r, const imu::NavState& n,
                          const geometry::SE3& T_b_c, Mat6x15* J_r = nullptr, Mat6x15* J_n = nullptr,
                          Mat6* J_extrinsics = nullptr);

/// Huber scaling of a link's information (eqs 24-25): the translation block
/// by c_t/‖e_t‖ when ‖e_t‖ > c_t, the rotation block by c_a/‖e_θ‖ when ‖e_θ‖ > c_a
/// (cross terms by the square root of both).
Mat6 huberWeightedInformation(const Mat6& information, const Vec6& residual, double c_t, double c_a);

}  // namespace edgevio::estimator
