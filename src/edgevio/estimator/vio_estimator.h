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
// estimator share no indices; which states are keyframes the caller says
// (it owns the keyframes). When the estimate blows up, the estimator restarts
// its window at the newest state by itself and says so. Without the IMU (mode
// edge+loop) the same window is a pose graph: states are joined by tracking
// and loop links only, and the gauge holds the oldest state's whole pose.
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "edgevio/common/time.h"
#include "edgevio/estimator/estimator_options.h"
#include "edgevio/estimator/external_check.h"
#include "edgevio/estimator/sliding_window.h"
#include "edgevio/imu/imu_types.h"

namespace edgevio::estimator {

/// Which end of the window marginalisation took a state from.
enum class Marginalization { kNone, kFront, kBack };
inline constexpr options::Choice<Marginalization> kMarginalizationChoices[] = {
    {Marginalization::kNone, "-", "the window was not full"},
    {Marginalization::kFront, "front", "the second-newest state (close to the keyframe, not a keyframe)"},
    {Marginalization::kBack, "back", "the oldest state"}};

/// What the two-way rule needs to know of the keyframes (METHOD.md §5).
struct KeyframeQuery {
  std::optional<std::int64_t> current;                ///< the keyframe frames are tracked against
  std::function<bool(std::int64_t)> is_keyframe;      ///< whether the state at a time is a keyframe
};

/// What one optimisation step did.
struct EstimatorUpdate {
  int iterations = 0;
  double initial_cost = 0.0, final_cost = 0.0;
  double solve_ms = 0.0, marginalize_ms = 0.0;
  Marginalization marginalized = Marginalization::kNone;
  std::int64_t marginalized_t_ns = -1;  ///< the state that left the window
  /// Non-empty: the estimate blew up (why), and the window restarted at the newest state.
  std::string reset_reason;
};

class VioEstimator {
 public:
  /// `start_gyro_bias`: what a reset falls back to when the gyroscope bias
  /// estimate is implausible (the static start's).
  VioEstimator(const EstimatorOptions& options, const imu::ImuNoise& noise, const geometry::SE3& T_b_c, bool inertial,
               const Vec3& start_gyro_bias = Vec3::Zero());
  bool inertial() const { return inertial_; }

  /// Starts a new window with one state. `velocity_known`: x's velocity and
  /// gyro bias are known (a static start measured them: zero velocity and the
  /// mean gyro reading); `attitude_known`: its roll and pitch are (a static
  /// start, or a restart across an IMU gap that tracking bridged). The
  /// initial prior says so.
  void initialize(std::int64_t t_ns, const imu::NavState& x, bool velocity_known, bool attitude_known);
  bool initialized() const { return !window_.states.empty(); }
  /// Restarts the window at t_ns after the inertial chain broke (an IMU gap):
  /// the newest state's biases carry over, at the pose T_w_b; v_w is the
  /// velocity's starting value (free in the window: estimated anew).
  /// `attitude_known`: T_w_b's roll and pitch get the initial tilt prior;
  /// otherwise the window estimates them anew from the IMU and the links.
  void restartAfterGap(std::int64_t t_ns, const geometry::SE3& T_w_b, const Vec3& v_w, bool attitude_known);

  const imu::NavState& newest() const { return window_.states.back().x; }
  std::int64_t newestTime() const { return window_.states.back().t_ns; }
  std::optional<imu::NavState> stateAt(std::int64_t t_ns) const;
  const Window& window() const { return window_; }
  const EstimatorOptions& options() const { return options_; }

  /// The window's estimate of the camera-IMU calibration, when it estimates one.
  const std::optional<CalibrationState>& calibration() const { return window_.calibration; }
  /// Body → camera with the window's correction (the calibration's without one).
  geometry::SE3 cameraExtrinsics() const { return estimator::cameraExtrinsics(window_); }
  /// The estimated camera-IMU time offset (IMU time minus camera time) [s]; 0 when not estimated.
  double timeOffset() const { return window_.calibration ? window_.calibration->time_offset_s : 0.0; }
  /// The IMU's time of a camera timestamp: shifted by the estimated time offset.
  std::int64_t imuTime(std::int64_t camera_t_ns) const { return camera_t_ns + toNanoseconds(timeOffset()); }

  /// Preintegrates the IMU from the newest state to t_ns (camera times; the
  /// IMU's times follow imuTime) at its biases;
  /// nullopt without IMU coverage or across a gap longer than max_imu_gap_s.
  std::optional<imu::Preintegration> preintegrateTo(const std::vector<imu::ImuSample>& imu, std::int64_t t_ns) const;
  /// Whether the IMU covers [t0_ns, t1_ns] with no gap longer than max_imu_gap_s.
  bool imuCovers(const std::vector<imu::ImuSample>& imu, std::int64_t t0_ns, std::int64_t t1_ns) const;

  /// Appends a state at t_ns linked to the newest by `pre`, initialised at the IMU prediction.
  void addState(std::int64_t t_ns, imu::Preintegration pre);

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
  /// With estimator.coupling tight, `image` is the newest frame's pyramid:
  /// the link enters as edge residuals when its reference state has points.
  std::optional<ExternalCheckResult> offerTrackingLink(std::int64_t t_ref_ns, const geometry::SE3& T_nr, const Mat6& covariance,
                                                       std::shared_ptr<const vision::EdgePyramid> image = nullptr);

  /// A keyframe's reference points for its tight links (estimator.coupling);
  /// false when its state is not in the window.
  bool setKeyframePoints(std::int64_t t_ns, KeyframePoints points);

  /// Gauss-Newton on the window, then marginalisation when it holds more
  /// than N states (the two-way rule: `alignment_good`, `keyframes`). When
  /// the estimate blew up, the window restarts at the newest state, placed at
  /// `restart_pose`, with its implausible velocity and biases reset.
  EstimatorUpdate optimize(bool alignment_good, const KeyframeQuery& keyframes, const geometry::SE3& restart_pose);
  /// optimize in parts, so that a driver can hand the frame's pose out
  /// early: solveWindow runs the first `iterations` of max_iterations
  /// Gauss-Newton iterations (or restarts the window as optimize does),
  /// finishSolve the rest, marginalizeWhenFull the marginalisation (only
  /// after a solve that did not restart the window). The three in a row,
  /// with any `iterations` > 0, leave the window as optimize does, unless
  /// the estimate fails the health check after the first part only (it then
  /// restarts there, before the pose is handed out). With `iterations` 0
  /// solveWindow solves the newest state alone (solveNewest), the others
  /// held, and all of the window's iterations follow in finishSolve, from there.
  EstimatorUpdate solveWindow(const geometry::SE3& restart_pose, int iterations);
  void finishSolve(const geometry::SE3& restart_pose, EstimatorUpdate* u);
  void marginalizeWhenFull(bool alignment_good, const KeyframeQuery& keyframes, EstimatorUpdate* u);

 private:
  std::optional<std::size_t> indexOf(std::int64_t t_ns) const;
  std::string checkHealth() const;
  /// Up to `iterations` Gauss-Newton iterations of the frame's solve (0: the newest state alone), then the health check.
  void iterate(int iterations, const geometry::SE3& restart_pose, EstimatorUpdate* u);
  void restartAfterBlowUp(const geometry::SE3& pose);
  bool addVisualLink(std::size_t r, std::size_t n, const geometry::SE3& T_nr, const Mat6& covariance,
                     std::shared_ptr<const vision::EdgePyramid> image = nullptr);
  /// The state two-way marginalisation removes (METHOD.md §5).
  std::size_t marginalizationVictim(bool alignment_good, const KeyframeQuery& keyframes) const;

  EstimatorOptions options_;
  imu::ImuNoise noise_;  ///< the calibration's densities times the *_inflation options
  bool inertial_ = true;
  Vec3 start_gyro_bias_;
  Window window_;
  imu::NavState predicted_newest_;  ///< IMU prediction of the newest state, for the external check
  int iterations_left_ = 0;         ///< Gauss-Newton iterations of the frame's solve still to run (finishSolve)
};

}  // namespace edgevio::estimator
