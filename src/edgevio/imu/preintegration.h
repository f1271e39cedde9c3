#pragma once
// IMU preintegration between two frames i and j (METHOD.md §4, paper §6.2,
// eqs 16-18), a value type that knows nothing about the window.
//
// Measurements â = a + b_a + n_a, ω̂ = ω + b_g + n_g. In frame b_i, with the
// midpoint rule over each IMU interval [k, k+1]:
//   γ_{k+1} = γ_k · Exp((½(ω̂_k + ω̂_{k+1}) − b_g)·δt)
//   ā = ½(γ_k (â_k − b_a) + γ_{k+1} (â_{k+1} − b_a))
//   α_{k+1} = α_k + β_k δt + ½ ā δt²,   β_{k+1} = β_k + ā δt
// so that, with g = [0, 0, 9.81] and Δt = t_j − t_i (METHOD.md §2):
//   p_j = p_i + v_i Δt − ½ g Δt² + R_i α,  v_j = v_i − g Δt + R_i β,  R_j = R_i γ.
//
// Error state δ = [δα, δθ, δβ, δb_a, δb_g] (15), with γ_true = γ·Exp(δθ). Its
// covariance P and the Jacobian J = ∂δ_j/∂δ_i (whose bias columns give the
// first-order bias correction) are propagated with the discrete error-state
// matrices F, G (eq 18; Forster et al. 2017, eqs 58-62), from P = 0, J = I.
// When the bias estimate moves by more than a threshold, repropagate().
#include <optional>
#include <vector>

#include "edgevio/geometry/so3.h"
#include "edgevio/imu/imu_types.h"

namespace edgevio::imu {

using Vec15 = Eigen::Matrix<double, 15, 1>;
using Mat15 = Eigen::Matrix<double, 15, 15>;

/// Index of each block in the 15-dimensional error state and residual.
enum Block : int { kP = 0, kR = 3, kV = 6, kBa = 9, kBg = 12 };

/// A frame's navigation state as the preintegration residual sees it.
struct NavState {
  geometry::SO3 R_w_b;
  Vec3 p_w = Vec3::Zero(), v_w = Vec3::Zero();
  Vec3 b_a = Vec3::Zero(), b_g = Vec3::Zero();
};

/// What a preintegration carries: the window needs the deltas' covariance and
/// bias Jacobians (and the readings, to integrate again with new biases); a
/// prediction from a state with these very biases needs the deltas alone, at
/// a twentieth of the cost.
enum class Propagation { kFull, kDeltasOnly };

class Preintegration {
 public:
  /// Biases are the linearisation point; `noise` holds the densities the
  /// covariance is propagated with (the estimator passes them inflated).
  Preintegration(const Vec3& b_a, const Vec3& b_g, const ImuNoise& noise, Propagation propagation = Propagation::kFull);

  /// Adds the interval between two consecutive IMU readings (dt in seconds).
  void integrate(double dt, const Vec3& acc0, const Vec3& gyr0, const Vec3& acc1, const Vec3& gyr1);
  /// Integrates again from the stored readings with new linearisation biases.
  void repropagate(const Vec3& b_a, const Vec3& b_g);

  double deltaT() const { return dt_sum_; }
  const Vec3& alpha() const { return alpha_; }
  const Vec3& beta() const { return beta_; }
  const geometry::SO3& gamma() const { return gamma_; }
  const Mat15& covariance() const { return P_; }
  const Mat15& jacobian() const { return J_; }
  const Vec3& linearizationBa() const { return b_a_; }
  const Vec3& linearizationBg() const { return b_g_; }
  /// The gyroscope's reading at the interval's end (Propagation::kFull; zero without readings).
  Vec3 lastGyro() const { return readings_.empty() ? Vec3::Zero() : readings_.back().gyr1; }

  /// Residual of eq 17 between states i and j, with the deltas corrected to
  /// first order for the biases of state i:
  ///   r_p = R_iᵀ(p_j − p_i − v_i Δt + ½ g Δt²) − α̂,   r_v = R_iᵀ(v_j − v_i + g Δt) − β̂,
  ///   r_θ = Log(γ̂ᵀ R_iᵀ R_j),   r_ba = b_aj − b_ai,   r_bg = b_gj − b_gi.
  /// (The paper writes r_θ = 2·vec(q); Log agrees to second order and makes
  /// the Jacobians exact.) Jacobians are with respect to the right-perturbed
  /// states [δp, δθ, δv, δb_a, δb_g], R ← R·Exp(δθ).
  Vec15 residual(const NavState& i, const NavState& j, Mat15* J_i = nullptr, Mat15* J_j = nullptr) const;

 private:
  struct Reading {
    double dt;
    Vec3 acc0, gyr0, acc1, gyr1;
  };
  void propagate(const Reading& m);
  /// P and J through one step (before γ moves on): w the step's rate, dR its rotation.
  void propagateCovariance(const Reading& m, const Vec3& w, const geometry::SO3& dR);

  Vec3 b_a_, b_g_;
  Propagation propagation_;
  Eigen::Matrix<double, 12, 12> Q_ = Eigen::Matrix<double, 12, 12>::Zero();
  double dt_sum_ = 0.0;
  Vec3 alpha_ = Vec3::Zero(), beta_ = Vec3::Zero();
  geometry::SO3 gamma_;
  Mat15 P_ = Mat15::Zero(), J_ = Mat15::Identity();
  std::vector<Reading> readings_;
};

/// Preintegration of the readings between t0 and t1 (cut by
/// forEachImuInterval); nullopt without IMU coverage of [t0, t1] or when two
/// consecutive readings are more than max_gap_s apart (a gap is not bridged).
std::optional<Preintegration> preintegrate(const std::vector<ImuSample>& imu, std::int64_t t0_ns, std::int64_t t1_ns,
                                           const Vec3& b_a, const Vec3& b_g, const ImuNoise& noise,
                                           double max_gap_s = 1.0, Propagation propagation = Propagation::kFull);

/// The IMU's prediction of state j from state i (METHOD.md §4), with the
/// deltas corrected to first order for i's biases as in the residual:
/// p_j = p_i + v_i Δt − ½gΔt² + R_i α̂, v_j = v_i − gΔt + R_i β̂, R_j = R_i γ̂.
NavState predictState(const NavState& i, const Preintegration& pre);

/// Gravity in the world frame as the propagation subtracts it (METHOD.md §2).
inline Vec3 gravity() { return Vec3(0.0, 0.0, 9.81); }

}  // namespace edgevio::imu
