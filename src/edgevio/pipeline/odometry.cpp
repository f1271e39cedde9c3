#include "edgevio/pipeline/odometry.h"

namespace edgevio::pipeline {

using geometry::SE3;

bool isImuMode(const std::string& mode) { return mode == "edge+imu" || mode == "edge+imu+loop"; }

std::string checkMode(const std::string& mode) {
  if (mode == "edge-only" || mode == "edge+imu") return {};
  if (mode == "edge+loop" || mode == "edge+imu+loop")
    return "mode '" + mode + "' is not implemented yet (loop closure follows); use edge-only or edge+imu";
  return "unknown mode '" + mode + "': use edge-only, edge+imu, edge+loop or edge+imu+loop";
}

Odometry::Odometry(const std::string& mode, const Config& config, const camera::StereoRig& rig,
                   const camera::StereoRectifier& rectifier, const std::vector<io::ImuSample>& imu,
                   const imu::StaticInit& init)
    : mode_(mode),
      config_(config),
      imu_(imu),
      init_(init),
      tracker_(rectifier, config.vision, config.alignment, config.tracking),
      estimator_(config.estimator, rig.imu, rectifier.T_b_rect(0)) {}

FrameResult Odometry::process(const tracking::StereoFrame& frame) {
  if (t_first_ < 0) t_first_ = frame.t_ns;
  FrameResult r = isImuMode(mode_) ? processEdgeImu(frame) : processEdgeOnly(frame);
  t_prev_ = frame.t_ns;
  return r;
}

FrameResult Odometry::processEdgeOnly(const tracking::StereoFrame& frame) {
  std::optional<geometry::SO3> dR;
  if (t_prev_ >= 0) {
    geometry::SO3 R;
    if (imu::integrateGyro(imu_, t_prev_, frame.t_ns, init_.gyro_bias, &R)) dR = R;
  }
  FrameResult r;
  r.track = tracker_.track(frame, dR, SE3(init_.R_w_b, Vec3::Zero()));
  r.T_w_b = r.track.T_w_b;
  return r;
}

void Odometry::restart(std::int64_t t_ns, imu::NavState x, bool static_start) {
  estimator_.initialize(t_ns, x, static_start);
  if (const auto kf = tracker_.keyframeTime(); kf && *kf == t_ns) estimator_.markKeyframe(t_ns);
}

FrameResult Odometry::processEdgeImu(const tracking::StereoFrame& frame) {
  FrameResult r;
  r.estimator_used = true;
  const auto poseOf = [](const imu::NavState& x) { return SE3(x.R_w_b, x.p_w); };
  if (!estimator_.initialized() && (imu_.empty() || imu_.front().t_ns > frame.t_ns)) {
    // The IMU has not started yet: track visually until it has.
    r = processEdgeOnly(frame);
    r.event = "no IMU reading before this frame: tracked without the estimator";
    return r;
  }
  if (!estimator_.initialized()) {
    // Static initialisation (METHOD.md §5): roll, pitch and gyro bias from the
    // IMU, yaw 0, position 0, velocity 0.
    imu::NavState x;
    x.R_w_b = init_.R_w_b;
    x.b_g = init_.gyro_bias;
    if (t_prev_ < 0) {
      r.track = tracker_.track(frame, poseOf(x), false);
    } else {
      r = processEdgeOnly(frame);
      r.estimator_used = true;
      x.R_w_b = r.track.T_w_b.so3();
      x.p_w = r.track.T_w_b.translation();
    }
    // Still inside the static window: the static start holds.
    const bool still_static = init_.is_static && static_cast<double>(frame.t_ns - t_first_) * 1e-9 < config_.tracking.static_init_window_s;
    restart(frame.t_ns, x, still_static);
    r.T_w_b = r.track.T_w_b;
    r.state = estimator_.newest();
    return r;
  }

  std::optional<imu::Preintegration> pre = estimator_.preintegrateTo(imu_, frame.t_ns);
  if (!pre) {
    // No IMU coverage between the frames: track from the last pose, and start
    // a new window here (the inertial chain is broken).
    const imu::NavState last = estimator_.newest();
    r.track = tracker_.track(frame, poseOf(last), false);
    imu::NavState x = last;
    x.R_w_b = r.track.T_w_b.so3();
    x.p_w = r.track.T_w_b.translation();
    restart(frame.t_ns, x, false);
    ++resets_;
    r.event = "no IMU coverage (or an IMU gap) since the previous frame: estimator restarted";
    r.T_w_b = r.track.T_w_b;
    r.state = estimator_.newest();
    return r;
  }

  const imu::NavState predicted = estimator::predictState(estimator_.newest(), *pre);
  tracker_.correctPoses([&](std::int64_t t) -> std::optional<SE3> {
    if (const auto x = estimator_.stateAt(t)) return poseOf(*x);
    return std::nullopt;
  });
  r.track = tracker_.track(frame, poseOf(predicted), true);
  const tracking::FrameTrack& t = r.track;
  const bool aligned = t.aligned && t.self_check_passed;
  estimator_.addState(frame.t_ns, std::move(*pre));
  if (t.promoted_previous) estimator_.markKeyframe(t.reference_t_ns);
  bool link_good = false;
  if (aligned) {
    const auto check = estimator_.offerTrackingLink(t.reference_t_ns, t.alignment.T_nr, t.alignment.covariance);
    if (check) r.external = *check;
    r.external_check = !check ? "no reference" : check->accepted ? "accepted" : "rejected";
    link_good = check && check->accepted;
    // A rejected link is dropped and the frame becomes a keyframe (METHOD.md §5);
    // so does a frame whose keyframe is no longer in the window (after a restart).
    if (!link_good && !t.keyframe) r.forced_keyframe = tracker_.promoteLastFrame();
  }
  if (t.keyframe || r.forced_keyframe) estimator_.markKeyframe(frame.t_ns);

  r.estimator = estimator_.optimize(link_good, tracker_.keyframeTime());
  if (!r.estimator.reset_reason.empty()) {
    // The estimate blew up: restart the window at this frame from the
    // tracker's pose (or the prediction), keeping what is still plausible.
    imu::NavState x = predicted;
    if (aligned) {
      x.R_w_b = t.T_w_b.so3();
      x.p_w = t.T_w_b.translation();
    }
    if (!x.v_w.allFinite() || x.v_w.norm() > config_.estimator.reset_velocity) x.v_w.setZero();
    if (!x.b_a.allFinite() || x.b_a.norm() > config_.estimator.reset_accel_bias) x.b_a.setZero();
    if (!x.b_g.allFinite() || x.b_g.norm() > config_.estimator.reset_gyro_bias) x.b_g = init_.gyro_bias;
    if (!x.p_w.allFinite() || !x.R_w_b.matrix().allFinite()) {
      x.R_w_b = t.T_w_b.so3();
      x.p_w = t.T_w_b.translation();
    }
    restart(frame.t_ns, x, false);
    ++resets_;
    r.event = "estimator reset: " + r.estimator.reset_reason;
  } else if (r.estimator.keyframe_left_window && tracker_.promoteLastFrame()) {
    // The keyframe was marginalised: later links need a reference in the window.
    r.forced_keyframe = true;
    estimator_.markKeyframe(frame.t_ns);
  }
  r.T_w_b = poseOf(estimator_.newest());
  r.state = estimator_.newest();
  return r;
}

}  // namespace edgevio::pipeline
