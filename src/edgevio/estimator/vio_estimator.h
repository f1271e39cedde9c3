#pragma once
// The sliding-window estimator of METHOD.md §5 around the window maths of
// sliding_window.h: it adds one state per frame linked to the previous one
// by preintegration, lets tracking links in through the IMU-aided external
// check, solves, and keeps the window at N states by two-way
// marginalisation:
//   front: remove the second-newest state when the last alignment was good,
//          it is not a keyframe and it is close to the current keyframe
//          (‖Δp‖/front_translation_m + angle/front_rotation_deg < 1);
//   back:  otherwise remove the oldest state.
// States are identified by their timestamps, so the tracker and the
// estimator share no indices. Without the IMU (mode edge+loop) the same
// window is a pose graph: states are joined by tracking and loop links only,
// and the gauge holds the oldest state's whole pose.
#include <cstdint>
#include <optional>
#include <string>

#include "edgevio/camera/calibration.h"
#include "edgevio/estimator/estimator_options.h"
#include "edgevio/estimator/external_check.h"
#include "edgevio/estimator/sliding_window.h"

namespace edgevio::estimator {

/// What one optimisation step did (a row of frames.csv).
struct EstimatorUpdate {
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;
  double solve_ms = 0.0, marginalize_ms = 0.0;
  std::string marginalized = "-";  ///< front | back | - (window not full)
  bool keyframe_left_window = false;  ///< the current keyframe was marginalised
  std::string reset_reason;           ///< non-empty: the estimate blew up and must be reinitialised
};

class VioEstimator {
 public:
  VioEstimator(const EstimatorOptions& options, const camera::ImuNoise& noise, const geometry::SE3& T_b_c,
               bool inertial = true);
  bool inertial() const { return inertial_; }

  /// Starts a new window with one state. `velocity_known`: x's velocity and
  /// gyro bias are known (a static start measured them: zero velocity and the
  /// mean gyro reading); `attitude_known`: its roll and pitch are (a static
  /// start, or a restart across an IMU gap that tracking bridged). The
  /// initial prior says so.
  void initialize(std::int64_t t_ns, const imu::NavState& x, bool velocity_known, bool attitude_known);
  bool initialized() const { return !window_.states.empty(); }

  const imu::NavState& newest() const { return window_.states.back().x; }
  std::int64_t newestTime() const { return window_.states.back().t_ns; }
  std::optional<imu::NavState> stateAt(std::int64_t t_ns) const;
  const Window& window() const { return window_; }
  const EstimatorOptions& options() const { return options_; }

  /// Preintegrates the IMU from the newest state to t_ns at its biases;
  /// nullopt without IMU coverage or across a gap longer than max_imu_gap_s.
  std::optional<imu::Preintegration> preintegrateTo(const std::vector<io::ImuSample>& imu, std::int64_t t_ns) const;

  /// Appends a state at t_ns linked to the newest by `pre`, initialised at
  /// the IMU prediction (then at `pose` when given: the tracker's estimate).
  void addState(std::int64_t t_ns, imu::Preintegration pre, const std::optional<geometry::SE3>& T_w_b = std::nullopt);

  /// Appends a state at the given pose without an inertial link (no IMU).
  void addStateWithoutImu(std::int64_t t_ns, const geometry::SE3& T_w_b);

  /// A link between two keyframes in the window: a loop closure (METHOD.md §6)
  /// or a back link (t_ref newer than t_new, loop/back_links.h); false when either has left it, or, with the IMU, when it is farther than
  /// loop_check_rotation_deg / loop_check_translation_m from the window's own
  /// estimate of the same relative pose. Both keyframes are in the window, a
  /// few seconds apart, where the IMU-backed estimate has drifted by
  /// centimetres; a loop link far from it matched a similar-looking place.
  bool addLoopLink(std::int64_t t_ref_ns, std::int64_t t_new_ns, const geometry::SE3& T_nr, const Mat6& covariance);

  /// Offers a tracking link from the state at t_ref to the newest state,
  /// measured T_nr with the alignment covariance. It enters only if the
  /// external check passes against the IMU prediction of the newest state
  /// (without the IMU it always enters).
  /// nullopt when the reference state is not in the window (any more).
  std::optional<ExternalCheckResult> offerTrackingLink(std::int64_t t_ref_ns, const geometry::SE3& T_nr, const Mat6& covariance);

  void markKeyframe(std::int64_t t_ns);

  /// Gauss-Newton on the window, then marginalisation when it holds more
  /// than N states. `alignment_good` and `keyframe_t_ns` drive the two-way rule.
  EstimatorUpdate optimize(bool alignment_good, std::optional<std::int64_t> keyframe_t_ns);

 private:
  std::optional<std::size_t> indexOf(std::int64_t t_ns) const;
  std::string checkHealth() const;

  SolverOptions solverOptions() const;
  bool addVisualLink(std::size_t r, std::size_t n, const geometry::SE3& T_nr, const Mat6& covariance);

  EstimatorOptions options_;
  camera::ImuNoise noise_;  ///< the calibration's densities times the *_inflation options
  bool inertial_ = true;
  Window window_;
  imu::NavState predicted_newest_;  ///< IMU prediction of the newest state, for the external check
};

}  // namespace edgevio::estimator
