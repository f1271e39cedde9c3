#pragma once
// The sliding window of METHOD.md §5 as plain data and free functions.
//
// Cost (eq 13): ½‖prior‖² + ½ Σ r_Iᵀ P⁻¹ r_I + ½ Σ r_Vᵀ W_V r_V over the states'
// 15-dimensional errors, minimised by Gauss-Newton (eqs 22-23). A tight
// tracking link (estimator.coupling) adds its keyframe's edge residuals
// instead of r_V, its points' inverse depths eliminated (keyframe_structure.h). The prior
// left by marginalisation is stored as a quadratic ½δᵀHδ + bᵀδ in the errors
// δ = x ⊟ x0 of the states it involves, x0 being their estimates when it was
// made. Marginalising a state folds every link that touches it, and the old
// prior, into a new prior by the Schur complement (eqs 20-21): nothing is
// thrown away. With first-estimate Jacobians, a state keeps the x0 of the
// first prior it entered for as long as it stays in one, and every factor's
// Jacobians with respect to it are taken there: the unobservable directions
// (world translation, rotation about gravity) then stay out of the prior.
#include <memory>
#include <optional>
#include <vector>

#include "edgevio/estimator/estimator_options.h"
#include "edgevio/estimator/factors.h"
#include "edgevio/estimator/keyframe_structure.h"
#include "edgevio/imu/preintegration.h"

namespace edgevio::estimator {

struct WindowState {
  std::int64_t t_ns = 0;  ///< the camera's timestamp
  imu::NavState x;
  /// The camera-IMU time offset its inertial link was integrated with (the
  /// state is the body at IMU time t_ns + time_offset_s) and the gyroscope's
  /// reading there: with the time offset estimated, the camera saw the body
  /// where this motion carried it over the offset's change since.
  double time_offset_s = 0.0;
  Vec3 gyro = Vec3::Zero();
  /// A keyframe's reference points, when its tracking links are tight (estimator.coupling).
  KeyframePoints points;
};

/// The camera-IMU calibration the window estimates beside its states
/// (options estimate_time_offset, estimate_cam_imu_rotation,
/// estimate_cam_imu_translation): the time offset (IMU time minus camera
/// time) and a correction of the body-camera extrinsics,
/// T_b_c = T_b_c(calibration)·(R_correction, t_correction), relative to the
/// calibration file's. Its error is padded to a state's 15 dimensions,
/// [δt, δφ, δp, 8 unused] (the correction perturbed on the right:
/// R ← R·Exp(δφ), t ← t + R·δp), so that the window's block algebra (envelope
/// Cholesky, Schur complement) handles it as one more block; a direction not
/// estimated (and every unused one) has unit information and never moves.
struct CalibrationState {
  bool time_offset = false, rotation = false, translation = false;  ///< which are estimated
  double time_offset_s = 0.0;
  geometry::SO3 R_correction;
  Vec3 t_correction = Vec3::Zero();
  /// The calibration file's uncertainty: a prior ½(δ/σ)² on each, around zero.
  double time_offset_sigma_s = 0.01, rotation_sigma_rad = 0.035, translation_sigma_m = 0.02;
};
inline constexpr long kCalibTimeOffset = 0, kCalibRotation = 1, kCalibTranslation = 4;

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
  /// State n's edge pyramid, for a tight tracking link (estimator.coupling):
  /// when set and state r has points, the window weighs the edge residuals
  /// of r's points in it (keyframe_structure.h) instead of `link`.
  std::shared_ptr<const vision::EdgePyramid> image;
};

struct MarginalPrior {
  std::vector<std::size_t> states;  ///< indices into Window::states
  std::vector<imu::NavState> x0;    ///< their linearisation point
  /// Whether the calibration block follows the states' (with the window's calibration), and its linearisation point.
  bool calibration = false;
  CalibrationState c0;
  Eigen::MatrixXd H;                ///< 15·(|states| + calibration) square
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
  geometry::SE3 T_b_c;  ///< body → camera whose relative poses the visual links measure (the calibration's)
  Gauge gauge = Gauge::kPositionYaw;
  std::optional<CalibrationState> calibration;  ///< estimated beside the states when set
};

/// Body → camera: the calibration's, corrected by the window's estimate when it has one.
geometry::SE3 cameraExtrinsics(const Window& w);
/// The calibration block's plus/minus (CalibrationState).
CalibrationState boxplus(const CalibrationState& c, const Eigen::Ref<const imu::Vec15>& d);
imu::Vec15 boxminus(const CalibrationState& c, const CalibrationState& c0);

struct SolveSummary {
  int iterations = 0;
  /// ½ Σ rᵀWr over the links plus the prior's ½δᵀHδ + bᵀδ (no constant term:
  /// negative values are normal; only differences within one solve mean anything).
  double initial_cost = 0.0, final_cost = 0.0;
  bool stopped = false;  ///< the last step vanished or was not finite: more iterations would not move the window
};

/// The state plus/minus operations of the 15-dimensional error.
imu::NavState boxplus(const imu::NavState& x, const Eigen::Ref<const imu::Vec15>& d);
imu::Vec15 boxminus(const imu::NavState& x, const imu::NavState& x0);

/// Total cost of the window at its current estimate (Huber-weighted).
double windowCost(const Window& w, const EstimatorOptions& o);

/// Gauss-Newton on the window: o.max_iterations steps at most, fewer once a
/// step is negligible.
SolveSummary solve(Window* w, const EstimatorOptions& o);

/// Gauss-Newton on the newest state alone, every other state and the
/// calibration held at their estimates (the links into it, and the prior
/// when it holds it): o.max_iterations steps of a 15x15 system at most. In
/// real time it gives the frame's pose before the window's solve
/// (estimator.realtime_pose_iterations: 0).
SolveSummary solveNewest(Window* w, const EstimatorOptions& o);

/// Removes state `index`, folding its links and the old prior into a new
/// prior; with o.front_marginalization_drops_links, for any state but the
/// oldest, the visual links measured in it are dropped instead of folded.
void marginalize(Window* w, std::size_t index, const EstimatorOptions& o);

}  // namespace edgevio::estimator
