#include "edgevio/tracking/edge_tracker.h"

#include <cmath>

#include "edgevio/vision/edge_pyramid.h"

namespace edgevio::tracking {

using geometry::SE3;
using geometry::SO3;

PreparedFrame prepareFrame(const StereoFrame& frame, const camera::StereoRectifier& rect, const vision::VisionOptions& vision) {
  return {frame.t_ns, frame.right, vision::buildEdgePyramid(frame.left, rect.rectifiedCamera(), vision)};
}

EdgeTracker::EdgeTracker(const camera::StereoRectifier& rectifier, const vision::VisionOptions& vision,
                         const AlignmentOptions& alignment, const TrackingOptions& tracking)
    : rect_(rectifier), vision_(vision), alignment_(alignment), tracking_(tracking), T_b_c_(rectifier.T_b_rect(0)) {}

std::shared_ptr<const KeyframeData> EdgeTracker::makeKeyframe(PreparedFrame frame) const {
  auto data = std::make_shared<KeyframeData>();
  data->t_ns = frame.t_ns;
  data->pyramid = std::move(frame.pyramid);
  const cv::Mat& right = frame.right.get();
  if (right.empty()) {  // no depth: alignment to it fails and tracking moves on to a new keyframe
    data->right_image_unreadable = true;
    data->depth.points.assign(data->pyramid.levels.size(), {});
  } else {
    data->depth = vision::computeKeyframeDepth(data->pyramid, right, rect_.baseline(), vision_);
  }
  return data;
}

AlignmentResult EdgeTracker::align(const vision::EdgePyramid& pyr, const KeyframeData& keyframe, const SE3& T_nr_init,
                                   const Prediction& prediction, PredictionCheck* check) const {
  std::optional<RotationPrior> rotation_prior;
  if (prediction.gyro_since && tracking_.rotation_prior_deg > 0)
    if (const auto R_br_bn = prediction.gyro_since(keyframe.t_ns)) {
      const SO3 R_b_c = prediction.T_b_c.value_or(T_b_c_).so3();
      const SO3 R_nr = R_b_c.inverse() * R_br_bn->inverse() * R_b_c;
      const double s0 = tracking_.rotation_prior_deg * kDegToRad, s1 = tracking_.rotation_prior_fraction * geometry::angle(R_nr);
      rotation_prior = RotationPrior{R_nr, std::sqrt(s0 * s0 + s1 * s1)};
    }
  const RotationPrior* prior = rotation_prior ? &*rotation_prior : nullptr;
  AlignmentResult r = alignEdges(keyframe.depth, pyr, T_nr_init, alignment_, -1, 0, prior);
  const auto realignFine = [&] {
    return alignEdges(keyframe.depth, pyr, T_nr_init, alignment_, tracking_.gyro_check_realign_levels - 1, 0, prior);
  };
  // Gyro check: the gyroscope's rotation over one frame is accurate to a
  // fraction of a degree; an alignment far from it has converged to a wrong
  // minimum (repetitive texture), so re-align from the prediction on the fine
  // levels only, where the basin cannot reach the wrong one.
  const auto rotationError = [&](const SE3& T_nr) { return geometry::angle(T_nr.so3().inverse() * T_nr_init.so3()) * kRadToDeg; };
  if (prediction.reliable != PredictionReliability::kNone && rotationError(r.T_nr) > tracking_.gyro_check_deg) {
    *check = PredictionCheck::kGyro;
    const AlignmentResult fine = realignFine();
    const double ms = r.ms;
    r = fine;
    r.ms += ms;
    if (rotationError(fine.T_nr) > tracking_.gyro_check_deg) r.self_check_passed = false;
    return r;
  }
  // Motion check: without the IMU the prediction is the last two frames'
  // motion, continued, and nothing downstream checks the pose. An alignment
  // whose camera lies beyond what any rig's acceleration reaches from it
  // went to another basin; from the prediction, on the fine levels, the
  // right one is the nearest.
  const auto cameraShift = [&](const SE3& T_nr) {
    return (T_nr.inverse().translation() - T_nr_init.inverse().translation()).norm();
  };
  if (prediction.max_translation_m && cameraShift(r.T_nr) > *prediction.max_translation_m) {
    *check = PredictionCheck::kMotion;
    const double ms = r.ms;
    r = realignFine();
    r.ms += ms;
    if (cameraShift(r.T_nr) > *prediction.max_translation_m) r.self_check_passed = false;
    return r;
  }
  // Translation check: parallel edges (stripes, planks) leave the alignment
  // free along them, and the coarse levels' wide basin can slide a stripe or
  // more. The IMU's prediction from the window's newest state is good to a few
  // centimetres over one frame; far from it, re-align from it on the fine
  // levels, and keep whichever result lies closer to the edges.
  if (prediction.reliable == PredictionReliability::kPose && tracking_.imu_translation_check_m > 0 &&
      (r.T_nr.translation() - T_nr_init.translation()).norm() > tracking_.imu_translation_check_m) {
    *check = PredictionCheck::kTranslation;
    AlignmentResult fine = realignFine();
    fine.ms += r.ms;
    if (fine.self_check_passed && fine.mean_distance_px <= r.mean_distance_px) return fine;
    r.ms = fine.ms;
  }
  return r;
}

KeyframeReason EdgeTracker::keyframeVote(const vision::EdgePyramid& pyr, const KeyframeData& keyframe,
                                         const AlignmentResult& a) const {
  if (a.visible_ratio < tracking_.keyframe_min_visible_ratio) return KeyframeReason::kPointsLeavingView;
  if (keyframe.referencePoints() < tracking_.keyframe_min_points) return KeyframeReason::kTooFewPoints;
  for (std::size_t l = 0; l < std::min<std::size_t>(2, pyr.levels.size()); ++l) {
    const double a_count = pyr.levels[l].edge_count, b_count = keyframe.pyramid.levels[l].edge_count;
    if (a_count > tracking_.keyframe_edge_ratio * b_count || b_count > tracking_.keyframe_edge_ratio * a_count)
      return KeyframeReason::kEdgeCountChanged;
  }
  return KeyframeReason::kNone;
}

Track EdgeTracker::track(const PreparedFrame& frame, const KeyframeData& keyframe, const SE3& T_w_b_keyframe,
                         const Prediction& prediction) const {
  Track t;
  const SE3 T_b_c = prediction.T_b_c.value_or(T_b_c_);
  const SE3 T_w_c_keyframe = T_w_b_keyframe * T_b_c;
  const SE3 T_nr_init = (prediction.T_w_b * T_b_c).inverse() * T_w_c_keyframe;
  t.alignment = align(frame.pyramid, keyframe, T_nr_init, prediction, &t.check);
  if (!t.passed()) return t;
  t.T_w_b = T_w_c_keyframe * t.alignment.T_nr.inverse() * T_b_c.inverse();
  t.keyframe_vote = keyframeVote(frame.pyramid, keyframe, t.alignment);
  return t;
}

}  // namespace edgevio::tracking
