// The per-frame stage code on synthetic tracks, without images: a tracker
// that knows the true motion stands in for edge alignment, the IMU is
// synthesised along the aggressive scenario. Checks the keyframe policy (one
// owner: references are always keyframes in the window), the promotion of
// the previous frame, the external check's refusals, the window's events
// (a keyframe leaving it, an IMU gap) and the poses.
#include "edgevio/pipeline/odometry.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <map>
#include <set>

#include "common/imu_scenario.h"
#include "edgevio/sim/random.h"

namespace edgevio::pipeline {
namespace {

using geometry::SE3;
using geometry::SO3;
using tracking::KeyframeReason;

constexpr std::int64_t kFrameNs = 50000000;  // 20 Hz

/// Aligns by looking the motion up in the truth, with noise of σ_t, σ_r per
/// link. Its knobs make tracking fail or vote the way real scenes do.
class FakeTracker final : public tracking::Tracker {
 public:
  FakeTracker(const test::ImuScenario& sc, const SE3& T_b_c) : sc_(sc), T_b_c_(T_b_c) {}

  /// A frame farther than this from its keyframe fails the self check (the view changed too much).
  std::int64_t max_span_ns = 10 * kFrameNs;
  /// Tracking votes for a new keyframe once the keyframe is this old (its points leave the view).
  std::int64_t keyframe_span_ns = 6 * kFrameNs;
  /// Frames whose link comes out this far off (a wrong minimum the self check cannot see).
  std::map<std::int64_t, SE3> corrupted;
  /// Frames whose alignment fails.
  std::set<std::int64_t> failing;
  double sigma_t = 0.002, sigma_r = 0.002;
  mutable int keyframes_made = 0;
  mutable std::vector<std::int64_t> made;  ///< the keyframes' times, in the order their data was made
  /// Per frame: the predicted camera position (in the estimate's world) and the prediction's bound on its error.
  mutable std::map<std::int64_t, std::pair<Vec3, std::optional<double>>> predictions;

  std::shared_ptr<const tracking::KeyframeData> makeKeyframe(tracking::PreparedFrame frame) const override {
    auto k = std::make_shared<tracking::KeyframeData>();
    k->t_ns = frame.t_ns;
    k->depth.points.assign(1, std::vector<Eigen::Vector3f>(2000));
    ++keyframes_made;
    made.push_back(frame.t_ns);
    return k;
  }

  tracking::Track track(const tracking::PreparedFrame& frame, const tracking::KeyframeData& keyframe, const SE3& T_w_b_keyframe,
                        const tracking::Prediction& prediction) const override {
    tracking::Track t;
    const Vec3 predicted_camera = (prediction.T_w_b * T_b_c_).translation();
    predictions[frame.t_ns] = {predicted_camera, prediction.max_translation_m};
    const std::int64_t span = frame.t_ns - keyframe.t_ns;
    t.alignment.self_check_passed = span <= max_span_ns && failing.count(frame.t_ns) == 0;
    if (!t.passed()) return t;
    sim::Rng rng(sim::hashCombine(static_cast<std::uint64_t>(frame.t_ns), static_cast<std::uint64_t>(keyframe.t_ns)));
    Vec6 noise;
    for (int k = 0; k < 6; ++k) noise[k] = rng.gaussian() * (k < 3 ? sigma_t : sigma_r);
    SE3 T_nr = (sc_.pose(frame.t_ns) * T_b_c_).inverse() * (sc_.pose(keyframe.t_ns) * T_b_c_) * SE3::exp(noise);
    if (const auto c = corrupted.find(frame.t_ns); c != corrupted.end()) T_nr = T_nr * c->second;
    t.alignment.T_nr = T_nr;
    t.alignment.covariance.setZero();
    t.alignment.covariance.diagonal() << Vec3::Constant(sigma_t * sigma_t), Vec3::Constant(sigma_r * sigma_r);
    t.alignment.visible_ratio = 1.0;
    t.T_w_b = T_w_b_keyframe * T_b_c_ * T_nr.inverse() * T_b_c_.inverse();
    // As EdgeTracker's motion check ends when the re-alignment stays in the wrong basin.
    if (prediction.max_translation_m &&
        ((t.T_w_b * T_b_c_).translation() - predicted_camera).norm() > *prediction.max_translation_m) {
      t.check = tracking::PredictionCheck::kMotion;
      t.alignment.self_check_passed = false;
      return t;
    }
    if (span >= keyframe_span_ns) t.keyframe_vote = KeyframeReason::kPointsLeavingView;
    return t;
  }

 private:
  const test::ImuScenario& sc_;
  SE3 T_b_c_;
};

const test::ImuScenario& scenario() {
  static const test::ImuScenario sc("aggressive");
  return sc;
}

/// Links carry their true covariance; the IMU its true densities.
Config testConfig() {
  Config c;
  c.estimator.visual_covariance_scale = 1.0;
  c.estimator.imu_noise_inflation = 1.0;
  c.estimator.gyro_bias_walk_inflation = c.estimator.accel_bias_walk_inflation = 1.0;
  c.back_links.keyframes = 0;  // back links align images
  return c;
}

struct OdometryRun {
  std::vector<FrameRecord> records;
  double max_position_error_m = 0.0;
};

/// Frames every 50 ms from 1 s (still) for `frames` frames, started at the true pose.
OdometryRun runOdometry(Mode mode, const Config& config, FakeTracker& tracker, int frames,
                const std::vector<imu::ImuSample>* imu_override = nullptr,
                const std::function<void(const FrameRecord&)>& posed = {}, bool realtime = false) {
  const test::ImuScenario& sc = scenario();
  const std::vector<imu::ImuSample>& imu = imu_override ? *imu_override : sc.imu.samples;
  const std::int64_t t0 = sc.spline.beginNs() + 1000000000LL;
  imu::StaticInit init;  // a static start at the true attitude, with the true gyro bias
  init.is_static = true;
  init.R_w_b = sc.pose(t0).so3();
  init.gyro_bias = sc.imu.b_g[static_cast<std::size_t>((t0 - sc.imu.samples.front().t_ns) / 5000000)];
  Odometry odometry(mode, config, tracker, sc.rig.T_b_c[0], sc.rig.imu, imu, init, realtime);
  OdometryRun run;
  const SE3 start = sc.pose(t0);
  for (int f = 0; f < frames; ++f) {
    tracking::PreparedFrame frame;
    frame.t_ns = t0 + f * kFrameNs;
    run.records.push_back(odometry.process(std::move(frame), posed));
    // The estimate starts at (0, yaw 0 of the static start): compare the motion since the start.
    const SE3 truth = SE3(init.R_w_b, Vec3::Zero()) * start.inverse() * sc.pose(frame.t_ns);
    run.max_position_error_m =
        std::max(run.max_position_error_m, (run.records.back().T_w_b.translation() - truth.translation()).norm());
  }
  return run;
}

/// Each aligned frame's reference is a keyframe made at or before it, not yet left behind by more than the window.
void expectReferencesAreKeyframes(const OdometryRun& run) {
  std::map<std::int64_t, bool> keyframes;
  for (const FrameRecord& r : run.records) {
    if (r.previous_promoted) keyframes[r.reference_t_ns] = true;
    if (r.aligned) {
      EXPECT_TRUE(keyframes.count(r.reference_t_ns)) << "frame " << r.t_ns << " tracked against a non-keyframe";
    }
    if (r.isKeyframe()) keyframes[r.t_ns] = true;
  }
}

TEST(Odometry, FollowsTheTruthWithKeyframesAsReferences) {
  FakeTracker tracker(scenario(), scenario().rig.T_b_c[0]);
  const OdometryRun run = runOdometry({true, false}, testConfig(), tracker, 200);
  std::size_t keyframes = 0, accepted = 0;
  for (const FrameRecord& r : run.records) {
    keyframes += static_cast<std::size_t>(r.keyframes_made);
    accepted += r.external_check == ExternalCheck::kAccepted;
    EXPECT_EQ(r.restart, WindowRestart::kNone);
  }
  std::printf("aggressive, 10 s of synthetic tracks: %zu keyframes, %zu accepted links, max position error %.4f m\n", keyframes,
              accepted, run.max_position_error_m);
  EXPECT_EQ(run.records.front().keyframe, KeyframeReason::kFirstFrame);
  expectReferencesAreKeyframes(run);
  // A new keyframe every 6 frames (the fake's vote), every link accepted.
  EXPECT_EQ(keyframes, static_cast<std::size_t>(tracker.keyframes_made));
  EXPECT_NEAR(static_cast<double>(keyframes), 200.0 / 6.0, 3.0);
  EXPECT_EQ(accepted, 199u);
  // As in VioEstimator.FollowsAggressiveMotionToTheAccuracyOfItsLinks: 33
  // keyframe hops of 2 mm chain to ~1.2 cm per axis; 5 cm is 3σ of the norm.
  EXPECT_LT(run.max_position_error_m, 0.05);
}

TEST(Odometry, APoseIsOutBeforeMarginalisationAndItsKeyframesDepthAndInRealTimeItsLoopClosure) {
  // The pose a consumer receives is the record's final one. Marginalisation
  // and a new keyframe's depth come after it (but a promoted previous
  // frame's depth before the frame is aligned to it); so does, in real time
  // only, the keyframe's loop closure, whose links then join the next solve.
  for (const bool realtime : {false, true}) {
    SCOPED_TRACE(realtime ? "real time" : "offline");
    FakeTracker tracker(scenario(), scenario().rig.T_b_c[0]);
    const std::int64_t failing = scenario().spline.beginNs() + 1000000000LL + 23 * kFrameNs;
    tracker.failing = {failing};
    std::vector<FrameRecord> posed;
    std::vector<std::size_t> made_at_pose;
    const OdometryRun run = runOdometry(
        Mode{}, testConfig(), tracker, 60, nullptr,
        [&](const FrameRecord& r) {
          posed.push_back(r);
          made_at_pose.push_back(tracker.made.size());
        },
        realtime);
    ASSERT_EQ(posed.size(), run.records.size());
    const auto madeAt = [&](std::int64_t t) {
      return static_cast<std::size_t>(std::find(tracker.made.begin(), tracker.made.end(), t) - tracker.made.begin());
    };
    int own_keyframes = 0, loop_closures_before_pose = 0, loop_closures = 0, promotions = 0, marginalized = 0;
    for (std::size_t i = 0; i < posed.size(); ++i) {
      const FrameRecord& r = run.records[i];
      EXPECT_EQ(posed[i].t_ns, r.t_ns);
      EXPECT_TRUE(posed[i].T_w_b.matrix() == r.T_w_b.matrix()) << i;
      EXPECT_EQ(posed[i].status, r.status) << i;
      EXPECT_LT(posed[i].estimator.marginalized_t_ns, 0) << i;
      loop_closures_before_pose += posed[i].loop_closure_ran;
      loop_closures += r.loop_closure_ran;
      marginalized += r.estimator.marginalized_t_ns >= 0;
      if (r.keyframe != KeyframeReason::kNone && !posed[i].loop_closure_ran) {
        // Its data was not needed before the pose: it is made after it.
        ++own_keyframes;
        EXPECT_GE(madeAt(r.t_ns), made_at_pose[i]) << i;
        EXPECT_LT(madeAt(r.t_ns), tracker.made.size()) << i;
      }
      if (r.t_ns == failing) {
        ASSERT_TRUE(r.previous_promoted);
        ++promotions;
        EXPECT_LT(madeAt(r.reference_t_ns), made_at_pose[i]);
      }
    }
    EXPECT_GT(loop_closures, 3);
    if (realtime) {
      EXPECT_EQ(loop_closures_before_pose, 0);
      EXPECT_GT(own_keyframes, 3);
    } else {
      EXPECT_GT(loop_closures_before_pose, 3);
    }
    EXPECT_EQ(promotions, 1);
    EXPECT_GT(marginalized, 20);  // 60 frames through a window of 30
  }
}

TEST(Odometry, AFailedAlignmentMakesThePreviousFrameTheKeyframe) {
  FakeTracker tracker(scenario(), scenario().rig.T_b_c[0]);
  tracker.keyframe_span_ns = 100 * kFrameNs;  // no votes: keyframes only when alignment fails
  tracker.max_span_ns = 4 * kFrameNs;
  const OdometryRun run = runOdometry({true, false}, testConfig(), tracker, 40);
  int promoted = 0;
  for (const FrameRecord& r : run.records) {
    if (!r.previous_promoted) continue;
    ++promoted;
    // The previous frame became the keyframe and the frame aligned to it.
    EXPECT_EQ(r.reference_t_ns, r.t_ns - kFrameNs);
    EXPECT_TRUE(r.selfCheckPassed());
    EXPECT_FALSE(r.isKeyframe());
  }
  // Frames 1-4 align to frame 0; frame 5 fails and frame 4 becomes the
  // keyframe; then every fourth frame: 5, 9, ..., 37.
  EXPECT_EQ(promoted, 9);
  expectReferencesAreKeyframes(run);
}

TEST(Odometry, ARejectedLinkMakesTheFrameAKeyframe) {
  FakeTracker tracker(scenario(), scenario().rig.T_b_c[0]);
  const std::int64_t t_bad = scenario().spline.beginNs() + 1000000000LL + 20 * kFrameNs;
  tracker.corrupted[t_bad] = SE3(SO3::exp(Vec3(0.0, 5.0 * kDegToRad, 0.0)), Vec3(0.1, 0.0, 0.0));
  const OdometryRun run = runOdometry({true, false}, testConfig(), tracker, 40);
  for (const FrameRecord& r : run.records) {
    if (r.t_ns != t_bad) continue;
    EXPECT_EQ(r.external_check, ExternalCheck::kRejected);
    EXPECT_NEAR(r.external.rotation_deg, 5.0, 0.5);
    EXPECT_EQ(r.keyframe, KeyframeReason::kLinkRejected);
  }
  expectReferencesAreKeyframes(run);
  EXPECT_LT(run.max_position_error_m, 0.02);  // the wrong link never entered the window
}

TEST(Odometry, AKeyframeLeavingTheWindowIsReplacedByTheNewestFrame) {
  FakeTracker tracker(scenario(), scenario().rig.T_b_c[0]);
  tracker.keyframe_span_ns = tracker.max_span_ns = 100 * kFrameNs;  // one keyframe as long as it stays in the window
  Config config = testConfig();
  config.estimator.window_size = 8;
  const OdometryRun run = runOdometry({true, false}, config, tracker, 60);
  int replaced = 0;
  for (const FrameRecord& r : run.records) {
    replaced += r.keyframe == KeyframeReason::kKeyframeLeftWindow;
    EXPECT_NE(r.external_check, ExternalCheck::kNoReference) << "frame " << r.t_ns << ": its keyframe had left the window";
  }
  EXPECT_GE(replaced, 1);
  expectReferencesAreKeyframes(run);
}

/// 0.3 s without IMU readings, from 0.5 s after the first frame of runOdometry.
struct ImuGap {
  std::int64_t begin = scenario().spline.beginNs() + 1500000000LL, end = begin + 300000000;
  std::vector<imu::ImuSample> imu;
  ImuGap() {
    for (const imu::ImuSample& s : scenario().imu.samples)
      if (s.t_ns <= begin || s.t_ns >= end) imu.push_back(s);
  }
};

TEST(Odometry, AnImuGapIsBridgedByTheEdgesAndRestartsTheWindowOnce) {
  const test::ImuScenario& sc = scenario();
  const ImuGap gap;
  const std::int64_t gap_begin = gap.begin, gap_end = gap.end;
  FakeTracker tracker(sc, sc.rig.T_b_c[0]);
  const OdometryRun run = runOdometry({true, false}, testConfig(), tracker, 40, &gap.imu);
  int restarts = 0, bridged = 0;
  for (std::size_t k = 1; k < run.records.size(); ++k) {
    const FrameRecord& r = run.records[k];
    const FrameRecord& before = run.records[k - 1];
    // Frames whose interval from their predecessor lacks readings (or starts
    // at the gap's last reading: preintegration begins at the reading before
    // the predecessor) are tracked by the edges alone and carry no window state.
    const bool in_gap = r.t_ns > gap_begin && before.t_ns <= gap_end;
    bridged += in_gap;
    if (in_gap) {
      EXPECT_FALSE(r.state.has_value()) << r.t_ns;
    }
    if (r.restart == WindowRestart::kNone) continue;
    ++restarts;
    EXPECT_EQ(r.restart, WindowRestart::kImuGap);
    EXPECT_EQ(r.events.back(), "IMU back after a gap: estimator restarted at the previous frame");  // the bridge held
    // The first frame after the gap restarts the window at its predecessor,
    // which is (or becomes) the keyframe the frame is linked to.
    EXPECT_TRUE(before.t_ns > gap_end && run.records[k - 2].t_ns <= gap_end) << r.t_ns;
    EXPECT_EQ(r.reference_t_ns, before.t_ns);
    EXPECT_TRUE(before.isKeyframe() || r.previous_promoted);
  }
  EXPECT_EQ(bridged, 7);  // the gap spans 6 frame intervals of 50 ms, and the next one starts at its last reading
  EXPECT_EQ(restarts, 1);
  expectReferencesAreKeyframes(run);
  EXPECT_LT(run.max_position_error_m, 0.05);
}

TEST(Odometry, InAnImuGapAnAlignmentBeyondTheConstantVelocityReachIsRefused) {
  // The gap of the test above; inside it one frame's alignment lands 0.5 m
  // off (another basin that passes the self check). Continuing the last
  // interval's motion misses a rig accelerating at a by a·dt·(dt + dt0)/2:
  // at 20 Hz and tracking.constant_velocity_max_accel_mps2 = 100 m/s², 0.25 m.
  const test::ImuScenario& sc = scenario();
  const ImuGap gap;
  const std::int64_t t0 = sc.spline.beginNs() + 1000000000LL, wrong = gap.begin + 3 * kFrameNs;
  const auto bridge = [&](double max_accel_mps2) {
    FakeTracker tracker(sc, sc.rig.T_b_c[0]);
    tracker.corrupted[wrong] = SE3(SO3(), Vec3(0.3, -0.4, 0.0));
    Config c = testConfig();
    c.tracking.constant_velocity_max_accel_mps2 = max_accel_mps2;
    return std::make_pair(runOdometry({true, false}, c, tracker, 40, &gap.imu), tracker.predictions);
  };
  const auto [run, predictions] = bridge(100.0);
  // The estimate's world: the static start's attitude at the origin (runOdometry).
  const SE3 truth_to_estimate = SE3(sc.pose(t0).so3(), Vec3::Zero()) * sc.pose(t0).inverse();
  int bounded = 0;
  double worst = 0.0;
  for (const auto& [t, p] : predictions) {
    const auto& [predicted_camera, bound_m] = p;
    if (!bound_m) continue;
    ++bounded;
    EXPECT_NEAR(*bound_m, 0.25, 1e-9) << t;
    const Vec3 true_camera = (truth_to_estimate * sc.pose(t) * sc.rig.T_b_c[0]).translation();
    worst = std::max(worst, (true_camera - predicted_camera).norm() / *bound_m);
  }
  // The aggressive scenario stays well inside 10 g: the truth is never near the bound.
  std::printf("%d bounded predictions; the truth at most %.2f of the bound from them\n", bounded, worst);
  EXPECT_LT(worst, 0.5);
  EXPECT_EQ(bounded, 7);  // every frame the gap bridges (the test above)
  for (const FrameRecord& r : run.records) {
    if (r.t_ns != wrong) continue;
    EXPECT_TRUE(r.motion_check_failed);
    EXPECT_FALSE(r.selfCheckPassed());
  }
  EXPECT_LT(run.max_position_error_m, 0.05);
  // Without the bound the wrong basin becomes the pose (and the next frames' prediction).
  const double unchecked_m = bridge(0.0).first.max_position_error_m;
  std::printf("max position error %.3f m; without the check %.3f m\n", run.max_position_error_m, unchecked_m);
  EXPECT_GT(unchecked_m, 0.3);
}

TEST(Odometry, AfterABridgeTheEdgesLostTheWindowEstimatesItsTiltAnew) {
  // Every frame in the gap fails its alignment: their poses are guesses, the
  // loss monitor says lost, and the restart leaves roll and pitch to the IMU
  // and the links (VioEstimator.ARestartWithAFreeTiltFindsItAnewFromTheImuAndTheLinks).
  const test::ImuScenario& sc = scenario();
  const ImuGap gap;
  FakeTracker tracker(sc, sc.rig.T_b_c[0]);
  for (std::int64_t t = sc.spline.beginNs() + 1000000000LL; t < gap.end + kFrameNs; t += kFrameNs)
    if (t > gap.begin) tracker.failing.insert(t);
  const OdometryRun run = runOdometry({true, false}, testConfig(), tracker, 40, &gap.imu);
  int restarts = 0;
  for (const FrameRecord& r : run.records) {
    if (r.restart == WindowRestart::kNone) continue;
    ++restarts;
    EXPECT_EQ(r.restart, WindowRestart::kImuGap);
    EXPECT_EQ(r.events.back(),
              "IMU back after a gap the edges lost: estimator restarted at the previous frame, roll and pitch estimated anew");
  }
  EXPECT_EQ(restarts, 1);
}

TEST(Odometry, EdgeOnlyChainsTheLinks) {
  FakeTracker tracker(scenario(), scenario().rig.T_b_c[0]);
  tracker.sigma_t = tracker.sigma_r = 0.0;
  const OdometryRun run = runOdometry({false, false}, testConfig(), tracker, 60);
  // Exact links, composed: the pose is the truth to rounding.
  EXPECT_LT(run.max_position_error_m, 1e-9);
  expectReferencesAreKeyframes(run);
  for (const FrameRecord& r : run.records) EXPECT_FALSE(r.state.has_value());
}

TEST(Odometry, AnAlignmentInAnotherBasinIsLostWhereTheAccelerometerDoesNotExplainItsStep) {
  // The aggressive scenario (up to 3 g) with 2 mm and 2 mrad link noise: the
  // accelerometer accounts for every step to the noise of a second
  // difference of three poses (sqrt(6) * 2 mm = 4.9 mm per axis; its norm
  // over 60 frames stays within 5 of those, 25 mm, a quarter of the 0.1 m bound),
  // in the visual and the IMU modes alike, and nothing is lost.
  for (const Mode mode : {Mode{false, false}, Mode{true, false}}) {
    FakeTracker tracker(scenario(), scenario().rig.T_b_c[0]);
    const OdometryRun run = runOdometry(mode, testConfig(), tracker, 60);
    double largest = 0.0;
    for (const FrameRecord& r : run.records) {
      EXPECT_EQ(r.status, TrackingStatus::kOk) << r.t_ns;
      if (std::isfinite(r.accel_disagreement_m)) largest = std::max(largest, r.accel_disagreement_m);
    }
    EXPECT_LT(largest, 0.025) << "imu " << mode.imu;
    EXPECT_TRUE(std::isfinite(run.records.back().accel_disagreement_m));
    std::printf("imu %d: largest accelerometer disagreement %.4f m\n", mode.imu, largest);
  }
  // Edge-only, frame 30 aligned 0.3 m off. It becomes the keyframe (its
  // predecessor's is six frames old), so the offset stays: lost at frame 30
  // and 31, whose second differences hold the step, trusted again from 32.
  FakeTracker tracker(scenario(), scenario().rig.T_b_c[0]);
  const std::int64_t t0 = scenario().spline.beginNs() + 1000000000LL;
  tracker.corrupted[t0 + 30 * kFrameNs] = SE3(SO3(), Vec3(0.3, 0.0, 0.0));
  const OdometryRun run = runOdometry({false, false}, testConfig(), tracker, 40);
  for (int f = 0; f < 40; ++f) EXPECT_EQ(run.records[f].status == TrackingStatus::kLost, f == 30 || f == 31) << f;
  EXPECT_TRUE(run.records[30].isKeyframe());
  EXPECT_EQ(run.records[30].lost_since_ns, t0 + 30 * kFrameNs);
  EXPECT_GT(run.records[30].accel_disagreement_m, 0.25);
  EXPECT_GT(run.max_position_error_m, 0.25);  // the loss marks where the error grew; it does not undo it
}

}  // namespace
}  // namespace edgevio::pipeline
