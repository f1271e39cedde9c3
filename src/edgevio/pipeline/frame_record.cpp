#include "edgevio/pipeline/frame_record.h"

#include <cstdio>
#include <limits>

namespace edgevio::pipeline {

namespace {

using R = FrameRecord;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

Cell integer(long long v) { return {Cell::Kind::kInteger, v, 0.0, ""}; }
Cell real(double v) { return {Cell::Kind::kReal, 0, v, ""}; }
Cell text(const char* v) { return {Cell::Kind::kText, 0, 0.0, v}; }

// The tracking link's components, the body's motion T_bn_br.
Cell linkT(const R& r, int i) { return real(r.link_T_bn_br.translation()[i]); }
Cell linkQ(const R& r, int i) { return real(r.link_T_bn_br.quaternion().coeffs()[i]); }  // coeffs(): x, y, z, w

Cell predictionCheck(const R& r) {
  using tracking::PredictionCheck;
  const PredictionCheck c = r.gyro_check_failed           ? PredictionCheck::kGyro
                            : r.translation_check_failed ? PredictionCheck::kTranslation
                            : r.motion_check_failed      ? PredictionCheck::kMotion
                                                         : PredictionCheck::kNone;
  return text(options::nameOf(tracking::kPredictionCheckChoices, c));
}

constexpr FrameColumn kColumns[] = {
      {"timestamp_ns", "ns", "the frame's time (its left image's)", [](const R& r) { return integer(r.t_ns); }},
      {"status", "-", "whether the estimate is trusted (see below)",
       [](const R& r) { return text(options::nameOf(kTrackingStatusChoices, r.status)); }},
      {"keyframe", "-", "1: the frame became a keyframe", [](const R& r) { return integer(r.isKeyframe()); }},
      {"keyframe_reason", "-", "why it became a keyframe (see below), or -",
       [](const R& r) { return text(options::nameOf(tracking::kKeyframeReasonChoices, r.keyframe)); }},
      {"previous_promoted", "-", "1: the alignment to the keyframe failed and the previous frame became the keyframe first",
       [](const R& r) { return integer(r.previous_promoted); }},
      {"aligned", "-", "1: an alignment was attempted (0 for a first frame)", [](const R& r) { return integer(r.aligned); }},
      {"self_check", "-", "1: the alignment passed its self check (METHOD.md §3)", [](const R& r) { return integer(r.selfCheckPassed()); }},
      {"reference_points", "-", "level-0 reference points of the keyframe it was aligned to",
       [](const R& r) { return integer(r.reference_points); }},
      {"points_used", "-", "of which landed in the image at the finest level", [](const R& r) { return integer(r.alignment.points_used); }},
      {"visible_ratio", "-", "their fraction", [](const R& r) { return real(r.alignment.visible_ratio); }, 4},
      {"iterations", "-", "Gauss-Newton iterations over all levels", [](const R& r) { return integer(r.alignment.iterations); }},
      {"mean_distance_px", "px", "mean distance of the visible points to the nearest edge at the finest level",
       [](const R& r) { return real(r.alignment.mean_distance_px); }, 4},
      {"translation_sigma_m", "m", "std. dev. of the alignment's translation along its weakest direction, for 1 px of edge noise",
       [](const R& r) { return real(r.alignment.translation_sigma_m); }, 4, true},
      {"frozen_image", "-", "1: the left image is the previous frame's to the last pixel (a stalled camera driver)",
       [](const R& r) { return integer(r.frozen_image); }},
      {"gyro_disagreement_deg", "deg",
       "the estimate's rotation since the previous frame against the gyroscope's over that time (with the newest gyroscope "
       "bias estimate, else the static start's)",
       [](const R& r) { return real(r.gyro_disagreement_deg); }, 3},
      {"implied_accel_mps2", "m/s^2",
       "the acceleration the estimate implies: the second difference of this and the previous two frames' positions",
       [](const R& r) { return real(r.implied_accel_mps2); }, 2},
      {"implied_speed_mps", "m/s", "the speed the estimate implies: this and the previous frame's positions apart over their time",
       [](const R& r) { return real(r.implied_speed_mps); }, 2},
      {"accel_disagreement_m", "m",
       "the position against the accelerometer's prediction from the previous two frames' poses (their velocity between "
       "them, the estimated attitudes, the newest bias estimates): a step no measured force explains",
       [](const R& r) { return real(r.accel_disagreement_m); }, 4},
      {"reference_timestamp_ns", "ns", "the keyframe's time: the tracking link's reference (-1: none)",
       [](const R& r) { return integer(r.reference_t_ns); }},
      {"link_tx", "m", "the tracking link as the body's motion T_bn_br (= T_w_bn^-1 T_w_br of a ground truth): translation x",
       [](const R& r) { return linkT(r, 0); }, 6},
      {"link_ty", "m", "... y", [](const R& r) { return linkT(r, 1); }, 6},
      {"link_tz", "m", "... z", [](const R& r) { return linkT(r, 2); }, 6},
      {"link_qx", "-", "... its rotation as a Hamilton quaternion: x", [](const R& r) { return linkQ(r, 0); }, 9},
      {"link_qy", "-", "... y", [](const R& r) { return linkQ(r, 1); }, 9},
      {"link_qz", "-", "... z", [](const R& r) { return linkQ(r, 2); }, 9},
      {"link_qw", "-", "... w", [](const R& r) { return linkQ(r, 3); }, 9},
      {"prediction_check", "-", "which check against the prediction re-aligned the frame (see below), or -",
       predictionCheck},
      {"external_check", "-", "what the IMU-aided external check did with the link (see below)",
       [](const R& r) { return text(options::nameOf(kExternalCheckChoices, r.external_check)); }},
      {"external_rotation_deg", "deg", "the link's rotation against the IMU's prediction",
       [](const R& r) { return real(r.external.rotation_deg); }, 3},
      {"external_translation_m", "m", "the link's translation against the IMU's prediction",
       [](const R& r) { return real(r.external.translation_m); }, 4},
      {"est_iterations", "-", "the window's Gauss-Newton iterations", [](const R& r) { return integer(r.estimator.iterations); }},
      {"est_initial_cost", "-",
       "the window's cost before them (the marginalisation prior enters without its constant: compare the two costs of one "
       "frame, not costs across frames)",
       [](const R& r) { return real(r.estimator.initial_cost); }, 6, true},
      {"est_final_cost", "-", "... and after them", [](const R& r) { return real(r.estimator.final_cost); }, 6, true},
      {"marginalized", "-", "which state two-way marginalisation removed (see below)",
       [](const R& r) { return text(options::nameOf(estimator::kMarginalizationChoices, r.estimator.marginalized)); }},
      {"restart", "-", "why the window restarted at this frame (see below), or -",
       [](const R& r) { return text(options::nameOf(kWindowRestartChoices, r.restart)); }},
      {"back_links", "-", "a new keyframe's back links that entered the window", [](const R& r) { return integer(r.back_links); }},
      {"loop_candidates", "-", "loop-closure candidates of a new keyframe", [](const R& r) { return integer(r.loop_candidates); }},
      {"loop_accepted", "-", "loop links that entered the window", [](const R& r) { return integer(r.loop_links); }},
      {"loop_window_rejected", "-", "loop links the estimator's loop check refused",
       [](const R& r) { return integer(r.loop_window_rejections); }},
      {"time_offset_ms", "ms",
       "the window's camera-IMU time offset, IMU time minus camera time (estimator.estimate_time_offset; NaN when off)",
       [](const R& r) { return real(r.calibration && r.calibration->time_offset ? 1e3 * r.calibration->time_offset_s : kNaN); },
       3},
      {"cam_imu_rotation_correction_deg", "deg",
       "the angle of the window's correction to the calibration's camera-IMU rotation (estimator.estimate_cam_imu_rotation; "
       "NaN when off)",
       [](const R& r) {
         return real(r.calibration && r.calibration->rotation ? geometry::angle(r.calibration->R_correction) * kRadToDeg : kNaN);
       },
       3},
      {"cam_imu_translation_correction_m", "m",
       "the length of the window's correction to the calibration's camera-IMU translation "
       "(estimator.estimate_cam_imu_translation; NaN when off)",
       [](const R& r) { return real(r.calibration && r.calibration->translation ? r.calibration->t_correction.norm() : kNaN); },
       4},
      {"canny_ms", "ms", "Canny on every pyramid level", [](const R& r) { return real(r.canny_ms); }, 3, false,
       {"Canny (pyramid)", "frame"}},
      {"dt_ms", "ms", "distance transform of every level", [](const R& r) { return real(r.dt_ms); }, 3, false,
       {"distance transform", "frame"}},
      {"lines_ms", "ms", "sub-pixel edge lines of level 0", [](const R& r) { return real(r.lines_ms); }, 3, false,
       {"edge lines (level 0)", "frame"}},
      {"bm_ms", "ms", "stereo block matching of the keyframes this frame made", [](const R& r) { return real(r.bm_ms); }, 3, false,
       {"block matching", "keyframe", true}},
      {"align_ms", "ms", "edge alignment, with its re-alignments", [](const R& r) { return real(r.alignment.ms); }, 3, false,
       {"edge alignment", "frame"}},
      {"back_link_ms", "ms", "back links of a new keyframe", [](const R& r) { return real(r.back_link_ms); }, 3, false,
       {"back links", "keyframe", true}},
      {"solve_ms", "ms", "the window's solve", [](const R& r) { return real(r.estimator.solve_ms); }, 3, false,
       {"optimisation (window solve)", "frame", true}},
      {"marginalize_ms", "ms", "two-way marginalisation", [](const R& r) { return real(r.estimator.marginalize_ms); }, 3, false,
       {"marginalisation", "frame", true}},
      {"loop_ms", "ms", "loop closure of a new keyframe", [](const R& r) { return real(r.loop_closure_ran ? r.loop_ms : 0.0); }, 3,
       false, {"loop closure", "keyframe", true}},
      {"total_ms", "ms", "the whole frame: decoding, rectification, pyramid, tracking, estimation",
       [](const R& r) { return real(r.total_ms); }, 3, false, {"total (incl. PNG decode, rectification)", "frame"}},
      {"latency_ms", "ms",
       "from the frame's arrival to its pose: in --realtime runs arrival is the frame's timestamp on the run's clock "
       "(its image read from its file before then, as a camera hands over pixels); offline, when the reader had read "
       "it (then it includes waiting in the full queues); rectification, pyramid, tracking and the solve count",
       [](const R& r) { return real(r.latency_ms); }, 3},
};

}  // namespace

const std::vector<FrameColumn>& frameColumns() {
  static const std::vector<FrameColumn> columns(std::begin(kColumns), std::end(kColumns));
  return columns;
}

std::string frameHeader() {
  std::string h;
  for (const FrameColumn& c : frameColumns()) h += (h.empty() ? "" : ",") + std::string(c.name);
  return h;
}

std::vector<std::string> frameCells(const FrameRecord& record) {
  std::vector<std::string> cells;
  cells.reserve(frameColumns().size());
  char buf[64];
  for (const FrameColumn& c : frameColumns()) {
    const Cell v = c.value(record);
    if (v.kind == Cell::Kind::kInteger) std::snprintf(buf, sizeof buf, "%lld", v.integer);
    else if (v.kind == Cell::Kind::kReal) std::snprintf(buf, sizeof buf, c.significant ? "%.*g" : "%.*f", c.precision, v.real);
    cells.emplace_back(v.kind == Cell::Kind::kText ? v.text : buf);
  }
  return cells;
}

std::string frameRow(const FrameRecord& record) {
  std::string row;
  for (const std::string& cell : frameCells(record)) row += (row.empty() ? "" : ",") + cell;
  return row;
}

}  // namespace edgevio::pipeline
