#pragma once
// The sliding window of METHOD.md §5 as plain data and free functions.
//
// Cost (eq 13): ½‖prior‖² + ½ Σ r_Iᵀ P⁻¹ r_I + ½ Σ r_Vᵀ W_V r_V over the states'
// 15-dimensional errors, minimised by Gauss-Newton (eqs 22-23). The prior
// left by marginalisation is stored as a quadratic ½δᵀHδ + bᵀδ in the errors
// δ = x ⊟ x0 of the states it involves, x0 being their estimates when it was
// made. Marginalising a state folds every link that touches it, and the old
// prior, into a new prior by the Schur complement (eqs 20-21): nothing is
// thrown away. With first-estimate Jacobians, a state keeps the x0 of the
// first prior it entered for as long as it stays in one, and every factor's
// Jacobians with respect to it are taken there: the unobservable directions
// (world translation, rotation about gravity) then stay out of the prior.
#include <vector>

#include "edgevio/estimator/factors.h"
#include "edgevio/imu/preintegration.h"

namespace edgevio::estimator {

struct WindowState {
  std::int64_t t_ns = 0;
  imu::NavState x;
  bool keyframe = false;
};

/// Preintegration between states i and j (indices into Window::states).
struct InertialLink {
  InertialLink(std::size_t from, std::size_t to, imu::Preintegration preintegration);
  /// Re-integrates with new linearisation biases (and updates the information).
  void repropagate(const Vec3& b_a, const Vec3& b_g);

  std::size_t i, j;
  imu::Preintegration pre;
  /// P⁻¹ of `pre`, kept with it: every linearisation needs it, it changes only with `pre`.
  imu::Mat15 information;
};

/// A tracking or loop-closure link from state r (its camera is the reference) to state n.
struct VisualLink {
  std::size_t r, n;
  RelativePoseLink link;
};

struct MarginalPrior {
  std::vector<std::size_t> states;  ///< indices into Window::states
  std::vector<imu::NavState> x0;    ///< their linearisation point
  Eigen::MatrixXd H;                ///< 15·|states| square
  Eigen::VectorXd b;
  bool empty() const { return states.empty(); }
};

struct Window {
  std::vector<WindowState> states;
  std::vector<InertialLink> inertial;
  std::vector<VisualLink> visual;
  MarginalPrior prior;
  geometry::SE3 T_b_c;  ///< body → camera whose relative poses the visual links measure
};

/// Options of the window solver (config section `estimator` when wired in).
struct SolverOptions {
  int max_iterations = 4;          ///< Gauss-Newton iterations per solve [-]
  double huber_translation_m = 0.1;  ///< c_t of eq 24 [m]
  double huber_rotation_deg = 2.0;   ///< c_a of eq 25 [deg]
  double damping = 1e-9;             ///< first multiple of the identity tried by the perturbed Cholesky [-]
  bool fix_gauge = true;             ///< hold the oldest state's position and yaw (METHOD.md §5): re-anchoring, or gauge_prior
  bool gauge_full_rotation = false;  ///< re-anchor its whole attitude too (no IMU: roll and pitch are unobservable)
  double min_step = 1e-9;            ///< stop when the step norm is below this [-]
  /// Gauge by a stiff zero-residual prior on the oldest state's position and
  /// yaw (all of its attitude with gauge_full_rotation) instead of moving the
  /// states after each step.
  bool gauge_prior = false;
  /// Jacobians of the states in the marginalisation prior at the prior's
  /// linearisation point (first-estimate Jacobians), residuals at the estimate.
  bool first_estimate_jacobians = false;
};

struct SolveSummary {
  int iterations = 0;
  /// ½ Σ rᵀWr over the links plus the prior's ½δᵀHδ + bᵀδ (no constant term:
  /// negative values are normal; only differences within one solve mean anything).
  double initial_cost = 0.0, final_cost = 0.0;
};

/// The state plus/minus operations of the 15-dimensional error.
imu::NavState boxplus(const imu::NavState& x, const Eigen::Ref<const imu::Vec15>& d);
imu::Vec15 boxminus(const imu::NavState& x, const imu::NavState& x0);

/// Total cost of the window at its current estimate (Huber-weighted).
double windowCost(const Window& w, const SolverOptions& o);

/// Gauss-Newton on the window.
SolveSummary solve(Window* w, const SolverOptions& o);

/// Removes state `index`, folding its links and the old prior into a new prior.
void marginalize(Window* w, std::size_t index, const SolverOptions& o);

}  // namespace edgevio::estimator
