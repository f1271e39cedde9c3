#include "edgevio/tracking/edge_tracker.h"

#include <cmath>

#include "edgevio/vision/edge_pyramid.h"

namespace edgevio::tracking {

using geometry::SE3;
using geometry::SO3;

std::string TrackingOptions::validate() const {
  if (!(keyframe_edge_ratio > 1.0)) return "keyframe_edge_ratio: must be > 1";
  if (keyframe_min_points < 0) return "keyframe_min_points: must be >= 0";
  if (!(keyframe_min_visible_ratio >= 0 && keyframe_min_visible_ratio <= 1)) return "keyframe_min_visible_ratio: in [0, 1]";
  if (translation_prior != "previous" && translation_prior != "constant_velocity")
    return "translation_prior: previous or constant_velocity";
  if (lost_after_failures < 1) return "lost_after_failures: at least 1";
  if (!(gyro_check_deg > 0)) return "gyro_check_deg: must be > 0";
  if (!(rotation_prior_deg >= 0)) return "rotation_prior_deg: must be >= 0 (0: off)";
  if (!(rotation_prior_fraction >= 0)) return "rotation_prior_fraction: must be >= 0";
  if (gyro_check_realign_levels < 1) return "gyro_check_realign_levels: at least 1";
  if (!(static_init_window_s > 0)) return "static_init_window_s: must be > 0";
  if (!(static_accel_std_max > 0 && static_gyro_std_max > 0)) return "static_*_std_max: must be > 0";
  return {};
}

EdgeTracker::EdgeTracker(const camera::StereoRectifier& rectifier, const vision::VisionOptions& vision,
                         const AlignmentOptions& alignment, const TrackingOptions& tracking)
    : rect_(rectifier), vision_(vision), alignment_(alignment), tracking_(tracking), T_b_c_(rectifier.T_b_rect(0)) {}

void EdgeTracker::makeKeyframe(vision::EdgePyramid pyramid, const LazyImage& right_full, const SE3& T_w_c, std::int64_t t_ns,
                               FrameTrack* out) {
  auto data = std::make_shared<KeyframeData>();
  data->t_ns = t_ns;
  if (right_full.get().empty()) {  // no depth: alignment to it fails and tracking moves on to a new keyframe
    out->right_image_unreadable = true;
    data->depth.points.assign(pyramid.levels.size(), {});
  } else {
    data->depth = vision::computeKeyframeDepth(pyramid, right_full.get(), rect_.baseline(), vision_);
  }
  data->pyramid = std::move(pyramid);
  out->bm_ms = data->depth.bm_ms;
  out->keyframe = true;
  keyframe_ = Keyframe{std::move(data), T_w_c};
}

AlignmentResult EdgeTracker::alignToKeyframe(const vision::EdgePyramid& pyr, const SE3& T_w_b_pred,
                                             PredictionReliability reliable, const GyroSince& gyro_since,
                                             FrameTrack* checks) const {
  const SE3 T_nr_init = (T_w_b_pred * T_b_c_).inverse() * keyframe_->T_w_c;
  std::optional<RotationPrior> rotation_prior;
  if (gyro_since && tracking_.rotation_prior_deg > 0)
    if (const auto R_br_bn = gyro_since(keyframe_->data->t_ns)) {
      const SO3 R_nr = T_b_c_.so3().inverse() * R_br_bn->inverse() * T_b_c_.so3();
      const double s0 = tracking_.rotation_prior_deg * kDegToRad, s1 = tracking_.rotation_prior_fraction * geometry::angle(R_nr);
      rotation_prior = RotationPrior{R_nr, std::sqrt(s0 * s0 + s1 * s1)};
    }
  const RotationPrior* prior = rotation_prior ? &*rotation_prior : nullptr;
  AlignmentResult r = alignEdges(keyframe_->data->depth, pyr, T_nr_init, alignment_, -1, 0, prior);
  const auto realignFine = [&] {
    return alignEdges(keyframe_->data->depth, pyr, T_nr_init, alignment_, tracking_.gyro_check_realign_levels - 1, 0, prior);
  };
  // Gyro check: the gyroscope's rotation over one frame is accurate to a
  // fraction of a degree; an alignment far from it has converged to a wrong
  // minimum (repetitive texture), so re-align from the prediction on the fine
  // levels only, where the basin cannot reach the wrong one.
  const auto rotationError = [&](const SE3& T_nr) {
    return geometry::angle(T_nr.so3().inverse() * T_nr_init.so3()) * 180.0 / kPi;
  };
  if (reliable != PredictionReliability::kNone && rotationError(r.T_nr) > tracking_.gyro_check_deg) {
    checks->gyro_check_failed = true;
    const AlignmentResult fine = realignFine();
    const double ms = r.ms;
    r = fine;
    r.ms += ms;
    if (rotationError(fine.T_nr) > tracking_.gyro_check_deg) r.self_check_passed = false;
    return r;
  }
  // Translation check: parallel edges (stripes, planks) leave the alignment
  // free along them, and the coarse levels' wide basin can slide a stripe or
  // more. The IMU's prediction from the window's newest state is good to a few
  // centimetres over one frame; far from it, re-align from it on the fine
  // levels, and keep whichever result lies closer to the edges.
  if (reliable == PredictionReliability::kPose && tracking_.imu_translation_check_m > 0 &&
      (r.T_nr.translation() - T_nr_init.translation()).norm() > tracking_.imu_translation_check_m) {
    checks->translation_check_failed = true;
    AlignmentResult fine = realignFine();
    fine.ms += r.ms;
    if (fine.self_check_passed && fine.mean_distance_px <= r.mean_distance_px) return fine;
    r.ms = fine.ms;
  }
  return r;
}

PreparedFrame prepareFrame(const StereoFrame& frame, const camera::StereoRectifier& rect, const vision::VisionOptions& vision) {
  return {frame.t_ns, frame.right, vision::buildEdgePyramid(frame.left, rect.rectifiedCamera(), vision)};
}

FrameTrack EdgeTracker::track(PreparedFrame frame, const std::optional<SO3>& R_prev_cur, const SE3& T_w_b_init) {
  if (!keyframe_) return track(std::move(frame), T_w_b_init, PredictionReliability::kNone);
  // Prediction: rotation from the gyroscope, translation from the previous estimate(s).
  const SO3 R_pred = T_w_b_prev_.so3() * (R_prev_cur ? *R_prev_cur : SO3());
  Vec3 p_pred = T_w_b_prev_.translation();
  if (tracking_.translation_prior == "constant_velocity") p_pred += T_w_b_prev_.translation() - T_w_b_prev2_.translation();
  return track(std::move(frame), SE3(R_pred, p_pred),
               R_prev_cur ? PredictionReliability::kRotation : PredictionReliability::kNone);
}

void EdgeTracker::correctPoses(const std::function<std::optional<SE3>(std::int64_t)>& pose_of) {
  if (keyframe_)
    if (const auto T = pose_of(keyframe_->data->t_ns)) keyframe_->T_w_c = *T * T_b_c_;
  if (previous_)
    if (const auto T = pose_of(previous_->t_ns)) previous_->T_w_b = *T;
}

bool EdgeTracker::promoteLastFrame() {
  if (!previous_ || previous_->t_ns != last_t_ns_) return false;
  FrameTrack promoted;
  makeKeyframe(std::move(previous_->pyramid), previous_->right, previous_->T_w_b * T_b_c_, previous_->t_ns, &promoted);
  previous_.reset();
  return true;
}

std::shared_ptr<const KeyframeData> EdgeTracker::keyframeData() const {
  return keyframe_ ? keyframe_->data : nullptr;
}

std::optional<std::int64_t> EdgeTracker::keyframeTime() const {
  if (!keyframe_) return std::nullopt;
  return keyframe_->data->t_ns;
}

FrameTrack EdgeTracker::track(PreparedFrame frame, const SE3& T_w_b_pred, PredictionReliability reliable,
                              const GyroSince& gyro_since) {
  FrameTrack out;
  out.t_ns = frame.t_ns;
  last_t_ns_ = frame.t_ns;
  vision::EdgePyramid pyr = std::move(frame.pyramid);
  out.canny_ms = pyr.canny_ms;
  out.dt_ms = pyr.dt_ms;
  out.lines_ms = pyr.lines_ms;

  if (!keyframe_) {
    out.T_w_b = T_w_b_pred;
    out.keyframe_reason = "first frame";
    makeKeyframe(std::move(pyr), frame.right, T_w_b_pred * T_b_c_, frame.t_ns, &out);
    T_w_b_prev_ = T_w_b_prev2_ = out.T_w_b;
    return out;
  }

  out.aligned = true;
  out.reference_points = static_cast<int>(keyframe_->data->depth.points.empty() ? 0 : keyframe_->data->depth.points[0].size());
  out.reference_t_ns = keyframe_->data->t_ns;
  out.alignment = alignToKeyframe(pyr, T_w_b_pred, reliable, gyro_since, &out);
  if (!out.alignment.self_check_passed && previous_) {
    // Motion since the keyframe was too large: the previous frame, tracked
    // and closer to this one, becomes the keyframe, and alignment is retried.
    FrameTrack promoted;
    makeKeyframe(std::move(previous_->pyramid), previous_->right, previous_->T_w_b * T_b_c_, previous_->t_ns, &promoted);
    previous_.reset();
    out.promoted_previous = true;
    out.reference_t_ns = keyframe_->data->t_ns;
    out.bm_ms += promoted.bm_ms;
    out.reference_points = static_cast<int>(keyframe_->data->depth.points[0].size());
    const double first_ms = out.alignment.ms;
    out.alignment = alignToKeyframe(pyr, T_w_b_pred, reliable, gyro_since, &out);
    out.alignment.ms += first_ms;
  }
  out.self_check_passed = out.alignment.self_check_passed;

  if (out.self_check_passed) {
    consecutive_failures_ = 0;
    out.T_w_b = keyframe_->T_w_c * out.alignment.T_nr.inverse() * T_b_c_.inverse();
    // Keyframe policy (METHOD.md §3).
    for (int l = 0; l < std::min<int>(2, static_cast<int>(pyr.levels.size())); ++l) {
      const double a = pyr.levels[static_cast<std::size_t>(l)].edge_count;
      const double b = keyframe_->data->pyramid.levels[static_cast<std::size_t>(l)].edge_count;
      if (a > tracking_.keyframe_edge_ratio * b || b > tracking_.keyframe_edge_ratio * a) out.keyframe_reason = "edge count changed";
    }
    if (out.reference_points < tracking_.keyframe_min_points) out.keyframe_reason = "too few reference points";
    if (out.alignment.visible_ratio < tracking_.keyframe_min_visible_ratio) out.keyframe_reason = "points leaving the view";
  } else {
    // The link is not used: the frame keeps its prediction and becomes a keyframe.
    ++consecutive_failures_;
    out.T_w_b = T_w_b_pred;
    out.keyframe_reason = "self check failed";
  }
  if (!out.keyframe_reason.empty()) {
    makeKeyframe(std::move(pyr), frame.right, out.T_w_b * T_b_c_, frame.t_ns, &out);
    previous_.reset();  // the keyframe is the previous frame now
  } else {
    previous_ = Previous{std::move(pyr), frame.right, out.T_w_b, frame.t_ns};
  }
  T_w_b_prev2_ = T_w_b_prev_;
  T_w_b_prev_ = out.T_w_b;
  return out;
}

}  // namespace edgevio::tracking
