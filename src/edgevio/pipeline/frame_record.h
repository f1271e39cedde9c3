#pragma once
// Everything that happened to one frame: the one record the pipeline fills,
// the writers turn into a row of frames.csv, the run summary counts, and
// `edgevio bench` reads back for its per-component times. Its columns are
// described once, in frameColumns(): name, unit, meaning and how to read the
// value from the record; frames.csv's header, its rows and the column
// reference (docs/outputs.md) all come from that table.
#include <cstdint>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "edgevio/estimator/external_check.h"
#include "edgevio/estimator/vio_estimator.h"
#include "edgevio/imu/preintegration.h"
#include "edgevio/tracking/alignment_picture.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::pipeline {

/// What the IMU-aided external check did with a frame's tracking link (METHOD.md §5).
enum class ExternalCheck { kNotRun, kAccepted, kRejected, kNoReference };
inline constexpr options::Choice<ExternalCheck> kExternalCheckChoices[] = {
    {ExternalCheck::kNotRun, "-", "no link was offered, or the mode has no IMU"},
    {ExternalCheck::kAccepted, "accepted", "the link entered the window"},
    {ExternalCheck::kRejected, "rejected", "the link was too far from the IMU's prediction"},
    {ExternalCheck::kNoReference, "no reference", "the keyframe had left the window"}};

/// Why the estimator's window restarted at a frame.
enum class WindowRestart { kNone, kImuGap, kBlowUp };
inline constexpr options::Choice<WindowRestart> kWindowRestartChoices[] = {
    {WindowRestart::kNone, "-", "the window went on"},
    {WindowRestart::kImuGap, "imu_gap", "the IMU is back after a gap the edges bridged: a new window from the previous frame"},
    {WindowRestart::kBlowUp, "blow_up", "the estimate blew up (see events): a new window at this frame"}};

/// Whether a frame's estimate can be trusted (pipeline/loss_monitor.h).
enum class TrackingStatus { kOk, kLost };
inline constexpr options::Choice<TrackingStatus> kTrackingStatusChoices[] = {
    {TrackingStatus::kOk, "ok", "tracking: the estimate is trusted"},
    {TrackingStatus::kLost, "lost", "inside a lost interval (summary.json lost_intervals): the pose is a guess"}};

struct FrameRecord {
  std::int64_t t_ns = 0;

  // Keyframes (pipeline/odometry.h's policy).
  tracking::KeyframeReason keyframe = tracking::KeyframeReason::kNone;  ///< why this frame became a keyframe
  bool previous_promoted = false;  ///< the alignment to the keyframe failed; the previous frame became one
  int keyframes_made = 0;          ///< keyframes this frame made (the previous one and/or this one)

  // Tracking.
  bool aligned = false;  ///< an alignment was attempted (every frame but a first one)
  tracking::AlignmentResult alignment;
  bool gyro_check_failed = false;         ///< an alignment was redone: its rotation was far from the gyroscope's
  bool translation_check_failed = false;  ///< an alignment was redone: its translation was far from the IMU's
  bool motion_check_failed = false;       ///< an alignment was redone: beyond the motion model's reach without the IMU
  int reference_points = 0;          ///< level-0 reference points of the keyframe it was aligned to
  std::int64_t reference_t_ns = -1;  ///< that keyframe's time: the tracking link's reference
  geometry::SE3 link_T_bn_br;        ///< the link as the body's motion (what a ground truth gives as T_w_bn⁻¹·T_w_br)

  // The window.
  ExternalCheck external_check = ExternalCheck::kNotRun;
  estimator::ExternalCheckResult external;
  estimator::EstimatorUpdate estimator;
  WindowRestart restart = WindowRestart::kNone;
  int back_links = 0;       ///< back links of a new keyframe that entered the window
  double back_link_ms = 0;
  bool loop_closure_ran = false;
  int loop_candidates = 0, loop_links = 0, loop_window_rejections = 0;
  double loop_ms = 0;

  // Times [ms] of the components (the layout of the paper's Table 1).
  double canny_ms = 0, dt_ms = 0, lines_ms = 0, bm_ms = 0, total_ms = 0;
  double latency_ms = 0;  ///< from the frame's arrival to its pose (the latency_ms column says what arrival is)

  // The result.
  TrackingStatus status = TrackingStatus::kOk;
  /// The frame's image is the previous frame's to the last pixel: a stalled
  /// camera driver repeating its buffer (a real sensor's noise never does).
  bool frozen_image = false;
  /// The angle between the estimate's rotation since the previous frame and
  /// the gyroscope's over that time [deg] (NaN: no IMU reading, a first frame).
  double gyro_disagreement_deg = std::numeric_limits<double>::quiet_NaN();
  /// |second difference| of the last three poses' positions [m/s^2] (NaN
  /// before the third frame): what the estimate claims the body accelerated.
  double implied_accel_mps2 = std::numeric_limits<double>::quiet_NaN();
  /// |first difference| of the last two poses' positions [m/s] (NaN on a first frame).
  double implied_speed_mps = std::numeric_limits<double>::quiet_NaN();
  /// How far the pose lies from where the accelerometer puts it, given the
  /// previous two poses [m] (NaN before the third frame or without IMU
  /// readings over both intervals): a step no force explains.
  double accel_disagreement_m = std::numeric_limits<double>::quiet_NaN();
  std::int64_t lost_since_ns = -1;  ///< where a loss this frame declared began (its first symptom); -1: none began here
  std::string lost_reason;          ///< why, when a loss began here
  geometry::SE3 T_w_b;                ///< the causal pose estimate of the frame
  std::optional<imu::NavState> state;  ///< the newest window state (velocity, biases) in the IMU modes
  /// The window's camera-IMU calibration estimate (estimator.estimate_time_offset, estimate_cam_imu_*).
  std::optional<estimator::CalibrationState> calibration;
  std::vector<std::string> events;     ///< for the log and summary.json: restarts, IMU gaps, unreadable images
  /// What the frame's alignment picture is drawn from, when the driver asked for pictures (not a column).
  std::shared_ptr<const tracking::AlignmentPicture> picture;

  bool selfCheckPassed() const { return alignment.self_check_passed; }
  bool isKeyframe() const { return keyframe != tracking::KeyframeReason::kNone; }
};

/// A value of a column, as its accessor reads it from a record.
struct Cell {
  enum class Kind { kInteger, kReal, kText } kind = Kind::kInteger;
  long long integer = 0;
  double real = 0.0;
  const char* text = "";
};

/// Which component of the paper's Table 1 a time column is, and per what.
struct Component {
  const char* name = nullptr;  ///< nullptr: not a component time
  const char* per = "frame";   ///< frame | keyframe
  bool when_run = false;       ///< averaged over the rows where it ran (> 0) only (always for per keyframe)
};

/// One column of frames.csv.
struct FrameColumn {
  const char* name;
  const char* unit;
  const char* meaning;
  Cell (*value)(const FrameRecord&);
  int precision = 0;  ///< digits after the point of a real (%.Nf); 0 with `significant`: %.Ng
  bool significant = false;
  Component component = {};
};

/// The columns of frames.csv, in order.
const std::vector<FrameColumn>& frameColumns();

/// frames.csv's header line (without the newline).
std::string frameHeader();
/// One record's cells as frames.csv writes them, in column order.
std::vector<std::string> frameCells(const FrameRecord& record);
/// One record as a frames.csv row (without the newline).
std::string frameRow(const FrameRecord& record);

}  // namespace edgevio::pipeline
