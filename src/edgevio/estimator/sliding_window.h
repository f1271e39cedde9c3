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

#include "edgevio/estimator/estimator_options.h"
#include "edgevio/estimator/factors.h"
#include "edgevio/imu/preintegration.h"

namespace edgevio::estimator {

struct WindowState {
  std::int64_t t_ns = 0;
  imu::NavState x;
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

/// What the gauge holds of the oldest state (METHOD.md §5): with the IMU,
/// its position and yaw (roll and pitch are observable through gravity);
/// without it, its whole pose; nothing when the prior already anchors the
/// window (a test problem).
enum class Gauge { kPositionYaw, kPose, kNone };

struct Window {
  std::vector<WindowState> states;
  std::vector<InertialLink> inertial;
  std::vector<VisualLink> visual;
  MarginalPrior prior;
  geometry::SE3 T_b_c;  ///< body → camera whose relative poses the visual links measure
  Gauge gauge = Gauge::kPositionYaw;
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
double windowCost(const Window& w, const EstimatorOptions& o);

/// Gauss-Newton on the window: o.max_iterations steps at most, fewer once a
/// step is negligible.
SolveSummary solve(Window* w, const EstimatorOptions& o);

/// Removes state `index`, folding its links and the old prior into a new prior.
void marginalize(Window* w, std::size_t index, const EstimatorOptions& o);

}  // namespace edgevio::estimator
