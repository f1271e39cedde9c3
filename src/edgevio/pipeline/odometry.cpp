#include "edgevio/pipeline/odometry.h"

#include <cstring>
#include <limits>

#include "edgevio/common/time.h"
#include "edgevio/loop/back_links.h"
#include "edgevio/loop/local_loop_closure.h"

namespace edgevio::pipeline {

using geometry::SE3;
using geometry::SO3;
using tracking::KeyframeReason;

namespace {
SE3 poseOf(const imu::NavState& x) { return SE3(x.R_w_b, x.p_w); }

bool samePixels(const cv::Mat& a, const cv::Mat& b) {
  if (a.empty() || a.size() != b.size() || a.type() != b.type()) return false;
  const std::size_t row_bytes = static_cast<std::size_t>(a.cols) * a.elemSize();
  for (int y = 0; y < a.rows; ++y)
    if (std::memcmp(a.ptr(y), b.ptr(y), row_bytes) != 0) return false;
  return true;
}
}  // namespace

Odometry::Odometry(Mode mode, const Config& config, const tracking::Tracker& tracker, const SE3& T_b_c,
                   const imu::ImuNoise& noise, const std::vector<imu::ImuSample>& imu, const imu::StaticInit& init,
                   bool realtime, bool pictures)
    : mode_(mode),
      config_(config),
      tracker_(tracker),
      imu_(imu),
      init_(init),
      T_b_c_(T_b_c),
      realtime_(realtime),
      pictures_(pictures),
      loss_(config.tracking) {
  if (mode.imu || mode.loop) estimator_.emplace(config.estimator, noise, T_b_c, mode.imu, init.gyro_bias);
}

FrameRecord Odometry::process(tracking::PreparedFrame frame, const std::function<void(const FrameRecord&)>& posed) {
  FrameRecord r;
  r.t_ns = frame.t_ns;
  r.canny_ms = frame.pyramid.canny_ms;
  r.dt_ms = frame.pyramid.dt_ms - frame.pyramid.lines_ms;
  r.lines_ms = frame.pyramid.lines_ms;
  if (t_first_ < 0) t_first_ = r.t_ns;
  if (!frame.pyramid.levels.empty()) {
    r.frozen_image = samePixels(frame.pyramid.levels[0].image, previous_image_);
    previous_image_ = frame.pyramid.levels[0].image;
  }
  // A frame that is not aligned (a first frame, a restart) still has a picture: its edges.
  if (pictures_ && !frame.pyramid.levels.empty())
    r.picture = std::make_shared<const tracking::AlignmentPicture>(
        tracking::AlignmentPicture{frame.pyramid.levels[0].image, frame.pyramid.levels[0].edges, {}});
  if (windowed() && estimator_->initialized())
    processInWindow(std::move(frame), &r);
  else
    processWithoutWindow(std::move(frame), &r);
  // The alignment's T_nr as the body's motion T_bn_br (what ground truth
  // gives directly: T_w_bn⁻¹·T_w_br), so the front end can be judged alone.
  const SE3 T_b_c = cameraExtrinsics();
  r.link_T_bn_br = T_b_c * r.alignment.T_nr * T_b_c.inverse();
  recordMotion(&r);
  loss_.update(&r);
  t_before_last_ = t_prev_;
  T_w_b_before_last_ = T_w_b_last_;
  t_prev_ = r.t_ns;
  T_w_b_last_ = r.T_w_b;
  if (posed) posed(r);
  finishFrame(&r);
  return r;
}

void Odometry::processWithoutWindow(tracking::PreparedFrame frame, FrameRecord* r) {
  const std::int64_t t = frame.t_ns;
  const bool imu_started = !imu_.empty() && imu_.front().t_ns <= t;
  if (windowed() && mode_.imu && !imu_started) r->events.push_back("no IMU reading before this frame: tracked without the estimator");
  if (!keyframes_.current()) {
    // The first frame: at the static start's attitude (METHOD.md §5), position 0.
    r->T_w_b = SE3(init_.R_w_b, Vec3::Zero());
    addKeyframe(std::move(frame), r->T_w_b, KeyframeReason::kFirstFrame, r);
  } else {
    const Tracked tracked = track(frame, gyroPrediction(T_w_b_last_, t), r);
    r->T_w_b = tracked.T_w_b;
    decideKeyframe(std::move(frame), tracked.T_w_b, tracked.vote, r);
  }
  if (windowed() && (imu_started || !mode_.imu)) startWindow(t, r);
}

void Odometry::startWindow(std::int64_t t_ns, FrameRecord* r) {
  // Static initialisation (METHOD.md §5): roll, pitch and gyro bias from the
  // IMU, velocity 0; the pose is where tracking put the frame. Still inside
  // the static window, the static start holds.
  imu::NavState x;
  x.R_w_b = r->T_w_b.so3();
  x.p_w = r->T_w_b.translation();
  x.b_g = init_.gyro_bias;
  const bool still_static = init_.is_static && toSeconds(t_ns - t_first_) < config_.tracking.static_init_window_s;
  estimator_->initialize(t_ns, x, mode_.imu && still_static, mode_.imu && still_static);
  keyframeForRestart(t_ns, r);
  if (mode_.imu) r->state = estimator_->newest();
}

void Odometry::processInWindow(tracking::PreparedFrame frame, FrameRecord* r) {
  const std::int64_t t = frame.t_ns;
  const imu::NavState last = estimator_->newest();
  std::optional<imu::Preintegration> pre;
  tracking::Prediction p;
  if (mode_.imu) {
    pre = estimator_->preintegrateTo(imu_, t);
    if (!pre) {
      if (!estimator_->imuCovers(imu_, t_prev_, t)) return bridgeImuGap(std::move(frame), r);
      restartAfterImuGap(r);
      pre = estimator_->preintegrateTo(imu_, t);
    }
    p.T_w_b = poseOf(imu::predictState(last, *pre));
    p.reliable = tracking::PredictionReliability::kPose;
    // The gyroscope alone, with the window's bias, since the keyframe: the
    // alignment's rotation prior. Not the window's relative estimate, which
    // the same links pulled: a prior from it would feed their errors back.
    p.gyro_since = [this, t, b_g = last.b_g](std::int64_t t_ref) { return gyroRotation(t_ref, t, b_g); };
  } else {
    p = gyroPrediction(poseOf(last), t);
  }
  const auto keyframe_before = keyframes_.currentTime();
  const Tracked tracked = track(frame, p, r);
  if (mode_.imu)
    estimator_->addState(t, std::move(*pre));
  else
    estimator_->addStateWithoutImu(t, tracked.T_w_b);
  const bool link_good = offerLink(frame, r);
  // A rejected link is dropped and the frame becomes a keyframe (METHOD.md
  // §5); so does a frame whose keyframe is no longer in the window.
  const KeyframeReason why = tracked.vote == KeyframeReason::kNone && r->selfCheckPassed() && !link_good
                                 ? KeyframeReason::kLinkRejected
                                 : tracked.vote;
  decideKeyframe(std::move(frame), tracked.T_w_b, why, r);
  after_pose_.loops = keyframes_.currentTime() != keyframe_before;
  if (tracked.vote != KeyframeReason::kNone && link_good) after_pose_.back_links_from = tracked.T_w_b;
  // Offline, as METHOD.md has it: a new keyframe's loop and back links enter
  // this frame's solve. In real time they follow the pose and join the next
  // solve (docs/method-deviations.md).
  if (!realtime_) linkNewKeyframe(r);
  solveWindow(link_good, tracked.T_w_b, r);
  r->T_w_b = poseOf(estimator_->newest());
  if (mode_.imu) r->state = estimator_->newest();
  r->calibration = estimator_->calibration();
}

void Odometry::bridgeImuGap(tracking::PreparedFrame frame, FrameRecord* r) {
  // No IMU between the previous frame and this one: the edges carry the pose,
  // tracked against the keyframe from a constant-velocity prediction (the
  // last two frames' motion, continued), and the window waits, holding its
  // last state, until the IMU is back.
  if (estimator_->newestTime() == t_prev_) r->events.push_back("IMU gap: tracked by the edges alone until the IMU is back");
  const Tracked tracked = track(frame, constantVelocityPrediction(r->t_ns), r);
  r->T_w_b = tracked.T_w_b;
  decideKeyframe(std::move(frame), tracked.T_w_b, tracked.vote, r);
}

void Odometry::restartAfterImuGap(FrameRecord* r) {
  // The IMU covers the time since the previous frame again: the window
  // restarts once, at that frame, at the pose the edges carried it to, with
  // the biases from before the gap. The velocity starts from the last two
  // frames' (the state before the gap is stale by the gap's length) and is
  // free in the window. The carried roll and pitch are held as after a
  // static start unless the bridge was lost: then they may be tens of
  // degrees off, and a tight prior on a wrong tilt fights the IMU until the
  // window blows up; left free, the IMU and the links find it anew
  // (docs/experiments/2026-12-03-imu-gap-motion-check.md).
  Vec3 v_w = estimator_->newest().v_w;
  if (t_before_last_ >= 0 && t_before_last_ < t_prev_)
    v_w = (T_w_b_last_.translation() - T_w_b_before_last_.translation()) / toSeconds(t_prev_ - t_before_last_);
  const bool bridge_lost = loss_.lost();
  estimator_->restartAfterGap(t_prev_, T_w_b_last_, v_w, !bridge_lost);
  r->restart = WindowRestart::kImuGap;
  r->events.push_back(bridge_lost ? "IMU back after a gap the edges lost: estimator restarted at the previous frame, roll and pitch "
                                    "estimated anew"
                                  : "IMU back after a gap: estimator restarted at the previous frame");
  keyframeForRestart(t_prev_, r);
}

tracking::Prediction Odometry::gyroPrediction(const SE3& T_w_b_last, std::int64_t t_ns) const {
  // Rotation from the gyroscope, translation from the previous estimate (METHOD.md §3).
  const auto dR = gyroRotation(t_prev_, t_ns, init_.gyro_bias);
  if (!dR) return constantVelocityPrediction(t_ns);
  tracking::Prediction p;
  p.T_w_b = SE3(T_w_b_last.so3() * *dR, T_w_b_last.translation());
  p.reliable = tracking::PredictionReliability::kRotation;
  return p;
}

tracking::Prediction Odometry::constantVelocityPrediction(std::int64_t t_ns) const {
  // Without the gyroscope: the last two frames' motion, continued. From the
  // last pose alone, a frame in fast motion can align into another basin
  // that passes the self check (docs/experiments/2026-12-02-imu-gap-bridge.md).
  tracking::Prediction p;
  p.T_w_b = T_w_b_last_;
  if (t_before_last_ < 0 || t_before_last_ >= t_prev_) return p;
  p.T_w_b = geometry::interpolate(T_w_b_before_last_, T_w_b_last_,
                                  1.0 + static_cast<double>(t_ns - t_prev_) / static_cast<double>(t_prev_ - t_before_last_));
  // Under a constant acceleration a, continuing the last interval dt0's
  // motion over the next dt misses by a·dt·(dt + dt0)/2.
  if (const double a = config_.tracking.constant_velocity_max_accel_mps2; a > 0) {
    const double dt = toSeconds(t_ns - t_prev_), dt0 = toSeconds(t_prev_ - t_before_last_);
    p.max_translation_m = 0.5 * a * dt * (dt + dt0);
  }
  return p;
}

Odometry::Tracked Odometry::track(const tracking::PreparedFrame& frame, const tracking::Prediction& prediction,
                                  FrameRecord* r) {
  r->aligned = true;
  tracking::Prediction p = prediction;
  if (windowed() && estimator_->calibration()) p.T_b_c = cameraExtrinsics();
  const auto alignToCurrent = [&] {
    makeKeyframeData(r);
    const Keyframe& k = *keyframes_.current();
    r->reference_t_ns = k.data->t_ns;
    r->reference_points = k.data->referencePoints();
    tracking::Track t = tracker_.track(frame, *k.data, keyframePose(k), p);
    r->gyro_check_failed |= t.check == tracking::PredictionCheck::kGyro;
    r->translation_check_failed |= t.check == tracking::PredictionCheck::kTranslation;
    r->motion_check_failed |= t.check == tracking::PredictionCheck::kMotion;
    return t;
  };
  tracking::Track t = alignToCurrent();
  if (!t.passed() && previous_) {
    // Motion since the keyframe was too large: the previous frame, tracked
    // and closer to this one, becomes the keyframe, and alignment is retried.
    const double first_ms = t.alignment.ms;
    promotePrevious(KeyframeReason::kNone, r);
    t = alignToCurrent();
    t.alignment.ms += first_ms;
  }
  r->alignment = t.alignment;
  if (r->picture)
    r->picture = std::make_shared<const tracking::AlignmentPicture>(tracking::AlignmentPicture{
        r->picture->image, r->picture->edges,
        tracking::reprojectReferencePoints(keyframes_.current()->data->depth, frame.pyramid, t.alignment.T_nr, config_.alignment)});
  // The link is not used when the alignment failed: the frame keeps its prediction.
  return t.passed() ? Tracked{t.T_w_b, t.keyframe_vote} : Tracked{p.T_w_b, KeyframeReason::kSelfCheckFailed};
}

bool Odometry::offerLink(const tracking::PreparedFrame& frame, FrameRecord* r) {
  if (!r->selfCheckPassed()) return false;
  // A tight link keeps the frame's pyramid (its images share the frame's pixels).
  std::shared_ptr<const vision::EdgePyramid> image;
  if (config_.estimator.coupling == estimator::Coupling::kTight) image = std::make_shared<const vision::EdgePyramid>(frame.pyramid);
  const auto check =
      estimator_->offerTrackingLink(r->reference_t_ns, r->alignment.T_nr, r->alignment.covariance, std::move(image));
  if (check) r->external = *check;
  if (mode_.imu) r->external_check = !check ? ExternalCheck::kNoReference : check->accepted ? ExternalCheck::kAccepted : ExternalCheck::kRejected;
  return check && check->accepted;
}

void Odometry::decideKeyframe(tracking::PreparedFrame frame, const SE3& T_w_b, KeyframeReason why, FrameRecord* r) {
  if (why == KeyframeReason::kNone)
    previous_ = Previous{std::move(frame), T_w_b};
  else
    addKeyframe(std::move(frame), T_w_b, why, r);
}

void Odometry::addKeyframe(tracking::PreparedFrame frame, const SE3& T_w_b, KeyframeReason why, FrameRecord* r) {
  makeKeyframeData(r);
  ++r->keyframes_made;
  if (frame.t_ns == r->t_ns)
    r->keyframe = why;
  else
    r->previous_promoted = true;
  // The window needs only its time; its depth (the right image decoded, block
  // matching) is made when a frame is aligned to it or once the pose is out.
  auto placeholder = std::make_shared<tracking::KeyframeData>();
  placeholder->t_ns = frame.t_ns;
  const bool in_window = windowed() && estimator_->stateAt(frame.t_ns).has_value();
  keyframes_.add(std::move(placeholder), T_w_b, in_window);
  unmade_keyframe_ = std::move(frame);
  previous_.reset();  // the keyframe is the previous frame now
}

void Odometry::makeKeyframeData(FrameRecord* r) {
  if (!unmade_keyframe_) return;
  std::shared_ptr<const tracking::KeyframeData> data = tracker_.makeKeyframe(std::move(*unmade_keyframe_));
  unmade_keyframe_.reset();
  r->bm_ms += data->depth.bm_ms;
  const estimator::EstimatorOptions& o = config_.estimator;
  if (windowed() && o.coupling == estimator::Coupling::kTight && !data->pyramid.levels.empty())
    estimator_->setKeyframePoints(
        data->t_ns, estimator::selectKeyframePoints(data->depth, data->pyramid.levels.front().camera, o.tight_points,
                                                    o.tight_disparity_sigma_px, config_.alignment.max_normal_angle_deg));
  if (data->right_image_unreadable) r->events.push_back("right image unreadable: keyframe without depth");
  keyframes_.setData(std::move(data));
}

bool Odometry::promotePrevious(KeyframeReason why, FrameRecord* r) {
  if (!previous_) return false;
  Previous p = std::move(*previous_);
  previous_.reset();
  addKeyframe(std::move(p.frame), p.T_w_b, why, r);
  return true;
}

void Odometry::solveWindow(bool link_good, const SE3& restart_pose, FrameRecord* r) {
  const estimator::EstimatorOptions& o = config_.estimator;
  r->estimator = estimator_->solveWindow(restart_pose, realtime_ ? o.realtime_pose_iterations : o.max_iterations);
  if (restartedAfterBlowUp(r)) return;
  after_pose_.finish_solve_restarting_at = restart_pose;
  after_pose_.marginalize_after_good_link = link_good;
}

bool Odometry::restartedAfterBlowUp(FrameRecord* r) {
  if (r->estimator.reset_reason.empty()) return false;
  // The estimate blew up and the estimator restarted its window at this frame.
  r->restart = WindowRestart::kBlowUp;
  r->events.push_back("estimator reset: " + r->estimator.reset_reason);
  after_pose_ = {};  // the keyframes it owed links to are gone from the window
  keyframeForRestart(r->t_ns, r);
  return true;
}

void Odometry::marginalize(bool link_good, FrameRecord* r) {
  estimator::KeyframeQuery keyframes;
  keyframes.current = keyframes_.currentTime();
  keyframes.is_keyframe = [this](std::int64_t t) { return keyframes_.isKeyframe(t); };
  estimator_->marginalizeWhenFull(link_good, keyframes, &r->estimator);
  const std::int64_t gone = r->estimator.marginalized_t_ns;
  if (gone < 0) return;
  const bool was_current = keyframes_.currentTime() == gone;
  keyframes_.leftWindow(gone);
  // Later links need a reference in the window.
  if (was_current && promotePrevious(KeyframeReason::kKeyframeLeftWindow, r)) after_pose_.loops = true;
}

void Odometry::finishFrame(FrameRecord* r) {
  if (after_pose_.finish_solve_restarting_at) {
    estimator_->finishSolve(*after_pose_.finish_solve_restarting_at, &r->estimator);
    restartedAfterBlowUp(r);  // then nothing else is owed but the keyframe's data
  }
  if (after_pose_.marginalize_after_good_link) marginalize(*after_pose_.marginalize_after_good_link, r);
  after_pose_.finish_solve_restarting_at.reset();
  after_pose_.marginalize_after_good_link.reset();
  linkNewKeyframe(r);
}

void Odometry::linkNewKeyframe(FrameRecord* r) {
  makeKeyframeData(r);
  if (after_pose_.loops) closeLoops(r);
  if (after_pose_.back_links_from) linkBack(*after_pose_.back_links_from, r);
  after_pose_.loops = false;
  after_pose_.back_links_from.reset();
}

void Odometry::keyframeForRestart(std::int64_t t_ns, FrameRecord* r) {
  keyframes_.windowRestarted();
  // The next frames must link to a state in the new window (otherwise they
  // would be dead-reckoned from a free velocity): this frame is the keyframe.
  if (keyframes_.currentTime() != t_ns) promotePrevious(KeyframeReason::kWindowRestart, r);
  if (keyframes_.currentTime() == t_ns) keyframes_.enterWindow(t_ns);
}

void Odometry::closeLoops(FrameRecord* r) {
  const Keyframe& latest = *keyframes_.current();
  const auto latest_state = estimator_->stateAt(latest.data->t_ns);
  if (!latest_state || !mode_.loop) return;
  std::vector<loop::LoopKeyframe> older;
  keyframes_.forEachInWindow([&](const Keyframe& k) {
    if (k.data->t_ns != latest.data->t_ns) older.push_back({k.data, keyframePose(k) * cameraExtrinsics()});
  });
  r->loop_closure_ran = true;
  loop::LoopStats stats;
  const double budget_ms = realtime_ ? config_.loop.realtime_max_ms : std::numeric_limits<double>::infinity();
  for (const loop::LoopLink& l : loop::closeLoops({latest.data, poseOf(*latest_state) * cameraExtrinsics()}, older, config_.loop,
                                                  config_.alignment, budget_ms, &stats)) {
    const bool added = estimator_->addLoopLink(l.t_ref_ns, l.t_new_ns, l.T_nr, l.covariance);
    r->loop_links += added;
    r->loop_window_rejections += !added;
  }
  r->loop_candidates += stats.candidates;
  r->loop_ms += stats.ms;
}

void Odometry::linkBack(const SE3& T_w_b, FrameRecord* r) {
  if (config_.back_links.keyframes == 0) return;
  const Keyframe& latest = *keyframes_.current();
  std::vector<loop::LoopKeyframe> previous;  // newest first, at the window's estimates
  keyframes_.forEachInWindow([&](const Keyframe& k) {
    if (k.data->t_ns < latest.data->t_ns) previous.insert(previous.begin(), {k.data, keyframePose(k) * cameraExtrinsics()});
  });
  // The tracker's pose of the new keyframe carries its tracking link, so the
  // first back link is checked against that link.
  loop::BackLinkStats stats;
  for (const loop::LoopLink& l :
       loop::backLinks({latest.data, T_w_b * cameraExtrinsics()}, previous, config_.back_links, config_.alignment, &stats))
    r->back_links += estimator_->addLoopLink(l.t_ref_ns, l.t_new_ns, l.T_nr, l.covariance);
  r->back_link_ms = stats.ms;
}

SE3 Odometry::keyframePose(const Keyframe& k) const {
  if (windowed())
    if (const auto x = estimator_->stateAt(k.data->t_ns)) return poseOf(*x);
  return k.T_w_b;
}

void Odometry::recordMotion(FrameRecord* r) const {
  const Vec3 b_g = r->state ? r->state->b_g : init_.gyro_bias;
  const Vec3 b_a = r->state ? r->state->b_a : Vec3::Zero();
  if (const auto dR = gyroRotation(t_prev_, r->t_ns, b_g))
    r->gyro_disagreement_deg = (dR->inverse() * T_w_b_last_.so3().inverse() * r->T_w_b.so3()).log().norm() * kRadToDeg;
  if (t_prev_ >= 0 && t_prev_ < r->t_ns)
    r->implied_speed_mps = (r->T_w_b.translation() - T_w_b_last_.translation()).norm() / toSeconds(r->t_ns - t_prev_);
  if (t_before_last_ < 0 || t_before_last_ >= t_prev_ || t_prev_ >= r->t_ns) return;
  const double dt1 = toSeconds(t_prev_ - t_before_last_), dt2 = toSeconds(r->t_ns - t_prev_);
  const Vec3 v1 = (T_w_b_last_.translation() - T_w_b_before_last_.translation()) / dt1;
  const Vec3 v2 = (r->T_w_b.translation() - T_w_b_last_.translation()) / dt2;
  r->implied_accel_mps2 = (2.0 * (v2 - v1) / (dt1 + dt2)).norm();
  // The accelerometer's account (METHOD.md §4's propagation, twice, the
  // velocity eliminated): v_0 is what carries p_0 to p_1 under the first
  // interval's readings, and p_2 follows from p_1 with v_1.
  const double max_gap_s = config_.estimator.max_imu_gap_s;
  const auto first = imu::preintegrate(imu_, imuTime(t_before_last_), imuTime(t_prev_), b_a, b_g, imu::ImuNoise{}, max_gap_s,
                                       imu::Propagation::kDeltasOnly);
  const auto second = imu::preintegrate(imu_, imuTime(t_prev_), imuTime(r->t_ns), b_a, b_g, imu::ImuNoise{}, max_gap_s,
                                        imu::Propagation::kDeltasOnly);
  if (!first || !second) return;
  imu::NavState x;
  x.R_w_b = T_w_b_before_last_.so3();
  x.p_w = T_w_b_before_last_.translation();
  x.b_a = b_a;
  x.b_g = b_g;
  const double d0 = first->deltaT();
  x.v_w = (T_w_b_last_.translation() - x.p_w + 0.5 * d0 * d0 * imu::gravity() - x.R_w_b * first->alpha()) / d0;
  x.v_w = imu::predictState(x, *first).v_w;
  x.R_w_b = T_w_b_last_.so3();
  x.p_w = T_w_b_last_.translation();
  r->accel_disagreement_m = (imu::predictState(x, *second).p_w - r->T_w_b.translation()).norm();
}

std::int64_t Odometry::imuTime(std::int64_t t_ns) const { return windowed() ? estimator_->imuTime(t_ns) : t_ns; }

std::optional<SO3> Odometry::gyroRotation(std::int64_t t0, std::int64_t t1, const Vec3& bias) const {
  SO3 R;
  if (t0 < 0) return std::nullopt;
  if (!imu::integrateGyro(imu_, imuTime(t0), imuTime(t1), bias, config_.estimator.max_imu_gap_s, &R)) return std::nullopt;
  return R;
}

}  // namespace edgevio::pipeline
