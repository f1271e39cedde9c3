#include "edgevio/pipeline/odometry.h"

#include <limits>

namespace edgevio::pipeline {

using geometry::SE3;

namespace {
SE3 poseOf(const imu::NavState& x) { return SE3(x.R_w_b, x.p_w); }
}  // namespace

bool isImuMode(const std::string& mode) { return mode == "edge+imu" || mode == "edge+imu+loop"; }
bool isLoopMode(const std::string& mode) { return mode == "edge+loop" || mode == "edge+imu+loop"; }

std::string checkMode(const std::string& mode) {
  if (mode == "edge-only" || mode == "edge+imu" || mode == "edge+loop" || mode == "edge+imu+loop") return {};
  return "unknown mode '" + mode + "': use edge-only, edge+imu, edge+loop or edge+imu+loop";
}

Odometry::Odometry(const std::string& mode, const Config& config, const camera::StereoRig& rig,
                   const camera::StereoRectifier& rectifier, const std::vector<io::ImuSample>& imu,
                   const imu::StaticInit& init, bool realtime)
    : mode_(mode),
      inertial_(isImuMode(mode)),
      loop_(isLoopMode(mode)),
      config_(config),
      imu_(imu),
      init_(init),
      T_b_c_(rectifier.T_b_rect(0)),
      tracker_(rectifier, config.vision, config.alignment, config.tracking),
      estimator_(config.estimator, rig.imu, rectifier.T_b_rect(0), isImuMode(mode)) {
  if (!realtime) config_.loop.max_ms = std::numeric_limits<double>::infinity();
}

FrameResult Odometry::process(tracking::PreparedFrame frame) {
  const std::int64_t t = frame.t_ns;
  if (t_first_ < 0) t_first_ = t;
  FrameResult r = mode_ == "edge-only" ? processEdgeOnly(std::move(frame)) : processWindowed(std::move(frame));
  t_prev_ = t;
  return r;
}

std::optional<geometry::SO3> Odometry::gyroRotation(std::int64_t t0, std::int64_t t1, const Vec3& bias) const {
  geometry::SO3 R;
  if (t0 < 0 || !imu::integrateGyro(imu_, t0, t1, bias, &R)) return std::nullopt;
  return R;
}

FrameResult Odometry::processEdgeOnly(tracking::PreparedFrame frame) {
  FrameResult r;
  const auto dR = gyroRotation(t_prev_, frame.t_ns, init_.gyro_bias);
  r.track = tracker_.track(std::move(frame), dR, SE3(init_.R_w_b, Vec3::Zero()));
  r.T_w_b = r.track.T_w_b;
  return r;
}

void Odometry::restart(std::int64_t t_ns, imu::NavState x, bool velocity_known, bool attitude_known) {
  estimator_.initialize(t_ns, x, velocity_known, attitude_known);
  keyframes_.clear();
  // The next frames must link to a state in the new window: this frame
  // becomes the keyframe (otherwise they would be dead-reckoned from a free velocity).
  if (const auto kf = tracker_.keyframeTime(); !kf || *kf != t_ns) tracker_.promoteLastFrame();
  if (const auto kf = tracker_.keyframeData(); kf && kf->t_ns == t_ns) {
    estimator_.markKeyframe(t_ns);
    keyframes_[t_ns] = kf;
  }
}

FrameResult Odometry::initializeWindow(tracking::PreparedFrame frame) {
  const std::int64_t t_ns = frame.t_ns;
  FrameResult r;
  // Static initialisation (METHOD.md §5): roll, pitch and gyro bias from the
  // IMU, yaw 0, position 0, velocity 0.
  imu::NavState x;
  x.R_w_b = init_.R_w_b;
  x.b_g = init_.gyro_bias;
  if (t_prev_ < 0) {
    r.track = tracker_.track(std::move(frame), poseOf(x), tracking::PredictionReliability::kNone);
  } else {
    r = processEdgeOnly(std::move(frame));
    x.R_w_b = r.track.T_w_b.so3();
    x.p_w = r.track.T_w_b.translation();
  }
  // Still inside the static window: the static start holds.
  const bool still_static = init_.is_static && static_cast<double>(t_ns - t_first_) * 1e-9 < config_.tracking.static_init_window_s;
  restart(t_ns, x, inertial_ && still_static, inertial_ && still_static);
  r.T_w_b = r.track.T_w_b;
  if (inertial_) r.state = estimator_.newest();
  return r;
}

void Odometry::closeLoops(FrameResult* r) {
  const auto latest_data = tracker_.keyframeData();
  const auto latest_state = estimator_.stateAt(latest_data->t_ns);
  if (!latest_state) return;
  keyframes_[latest_data->t_ns] = latest_data;
  std::vector<loop::LoopKeyframe> older;
  for (auto it = keyframes_.begin(); it != keyframes_.end();) {
    const auto x = estimator_.stateAt(it->first);
    if (!x) {
      it = keyframes_.erase(it);  // left the window
      continue;
    }
    if (it->first != latest_data->t_ns) older.push_back({it->second, poseOf(*x) * T_b_c_});
    ++it;
  }
  if (!loop_) return;
  r->loop_ran = true;
  const loop::LoopKeyframe latest{latest_data, poseOf(*latest_state) * T_b_c_};
  for (const loop::LoopLink& l : loop::closeLoops(latest, older, config_.loop, config_.alignment, &r->loop)) {
    const bool added = estimator_.addLoopLink(l.t_ref_ns, l.t_new_ns, l.T_nr, l.covariance);
    loop_closures_ += added;
    r->loop.window_rejections += !added;
  }
}

void Odometry::linkBack(const tracking::FrameTrack& t, FrameResult* r) {
  const auto latest = tracker_.keyframeData();
  if (config_.back_links.keyframes == 0 || !latest || latest->t_ns != t.t_ns) return;
  std::vector<loop::LoopKeyframe> previous;  // newest first, at the window's estimates
  for (auto it = keyframes_.rbegin(); it != keyframes_.rend(); ++it)
    if (it->first < t.t_ns)
      if (const auto x = estimator_.stateAt(it->first)) previous.push_back({it->second, poseOf(*x) * T_b_c_});
  // The tracker's pose of the new keyframe carries its tracking link, so the
  // first back link is checked against that link.
  const loop::LoopKeyframe newest{latest, t.T_w_b * T_b_c_};
  for (const loop::LoopLink& l : loop::backLinks(newest, previous, config_.back_links, config_.alignment, &r->back))
    r->back_links_added += estimator_.addLoopLink(l.t_ref_ns, l.t_new_ns, l.T_nr, l.covariance);
  back_links_ += static_cast<std::size_t>(r->back_links_added);
}

FrameResult Odometry::processWindowed(tracking::PreparedFrame frame) {
  const std::int64_t t_ns = frame.t_ns;
  if (inertial_ && !estimator_.initialized() && (imu_.empty() || imu_.front().t_ns > t_ns)) {
    // The IMU has not started yet: track visually until it has.
    FrameResult r = processEdgeOnly(std::move(frame));
    r.event = "no IMU reading before this frame: tracked without the estimator";
    return r;
  }
  if (!estimator_.initialized()) return initializeWindow(std::move(frame));

  FrameResult r;
  const imu::NavState last = estimator_.newest();
  std::optional<imu::Preintegration> pre;
  SE3 T_w_b_pred = poseOf(last);
  auto reliable = tracking::PredictionReliability::kNone;
  if (inertial_) {
    pre = estimator_.preintegrateTo(imu_, t_ns);
    if (!pre) {
      // No IMU coverage between the frames: track from the last pose, and
      // start a new window here (the inertial chain is broken).
      r.track = tracker_.track(std::move(frame), poseOf(last), tracking::PredictionReliability::kNone);
      imu::NavState x = last;
      x.R_w_b = r.track.T_w_b.so3();
      x.p_w = r.track.T_w_b.translation();
      restart(t_ns, x, false, true);  // the attitude and biases carry over; the velocity is re-estimated
      ++resets_;
      r.event = "no IMU coverage (or an IMU gap) since the previous frame: estimator restarted";
      r.T_w_b = r.track.T_w_b;
      r.state = estimator_.newest();
      return r;
    }
    T_w_b_pred = poseOf(estimator::predictState(last, *pre));
    reliable = tracking::PredictionReliability::kPose;
  } else if (const auto dR = gyroRotation(t_prev_, t_ns, init_.gyro_bias)) {
    T_w_b_pred = SE3(last.R_w_b * *dR, last.p_w);  // the paper's guess: gyro rotation, previous translation
    reliable = tracking::PredictionReliability::kRotation;
  }

  tracker_.correctPoses([&](std::int64_t t) -> std::optional<SE3> {
    if (const auto x = estimator_.stateAt(t)) return poseOf(*x);
    return std::nullopt;
  });
  const auto keyframe_before = tracker_.keyframeTime();
  // The gyroscope alone, with the window's bias, since the keyframe: the
  // alignment's rotation prior. Not the window's relative estimate, which
  // the same links pulled: a prior from it would feed their errors back.
  tracking::EdgeTracker::GyroSince gyro_since;
  if (inertial_) gyro_since = [&](std::int64_t t_ref) { return gyroRotation(t_ref, t_ns, last.b_g); };
  r.track = tracker_.track(std::move(frame), T_w_b_pred, reliable, gyro_since);
  const tracking::FrameTrack& t = r.track;
  const bool aligned = t.aligned && t.self_check_passed;
  if (inertial_)
    estimator_.addState(t_ns, std::move(*pre));
  else
    estimator_.addStateWithoutImu(t_ns, aligned ? t.T_w_b : T_w_b_pred);
  if (t.promoted_previous) estimator_.markKeyframe(t.reference_t_ns);
  bool link_good = false;
  if (aligned) {
    const auto check = estimator_.offerTrackingLink(t.reference_t_ns, t.alignment.T_nr, t.alignment.covariance);
    if (check) r.external = *check;
    if (inertial_) r.external_check = !check ? "no reference" : check->accepted ? "accepted" : "rejected";
    link_good = check && check->accepted;
    // A rejected link is dropped and the frame becomes a keyframe (METHOD.md §5);
    // so does a frame whose keyframe is no longer in the window (after a restart).
    if (!link_good && !t.keyframe) r.forced_keyframe = tracker_.promoteLastFrame();
  }
  if (t.keyframe || r.forced_keyframe) estimator_.markKeyframe(t_ns);
  if (tracker_.keyframeTime() != keyframe_before) closeLoops(&r);
  if (t.keyframe && link_good) linkBack(t, &r);

  r.estimator = estimator_.optimize(link_good, tracker_.keyframeTime());
  if (!r.estimator.reset_reason.empty()) {
    // The estimate blew up: restart the window at this frame from the
    // tracker's pose (or the prediction), keeping what is still plausible.
    imu::NavState x = estimator_.newest();
    x.R_w_b = (aligned ? t.T_w_b : T_w_b_pred).so3();
    x.p_w = (aligned ? t.T_w_b : T_w_b_pred).translation();
    if (!x.v_w.allFinite() || x.v_w.norm() > config_.estimator.reset_velocity) x.v_w.setZero();
    if (!x.b_a.allFinite() || x.b_a.norm() > config_.estimator.reset_accel_bias) x.b_a.setZero();
    if (!x.b_g.allFinite() || x.b_g.norm() > config_.estimator.reset_gyro_bias) x.b_g = init_.gyro_bias;
    restart(t_ns, x, false, false);
    ++resets_;
    r.event = "estimator reset: " + r.estimator.reset_reason;
  } else if (r.estimator.keyframe_left_window && tracker_.promoteLastFrame()) {
    // The keyframe was marginalised: later links need a reference in the window.
    r.forced_keyframe = true;
    estimator_.markKeyframe(t_ns);
    closeLoops(&r);
  }
  r.T_w_b = poseOf(estimator_.newest());
  if (inertial_) r.state = estimator_.newest();
  return r;
}

}  // namespace edgevio::pipeline
