// When a run declares its estimate lost, and when it trusts it again.
#include "edgevio/pipeline/loss_monitor.h"

#include <gtest/gtest.h>

#include <functional>
#include <limits>

namespace edgevio::pipeline {
namespace {

/// The loss options with these values; the acceleration signal off unless given.
tracking::TrackingOptions lossOptions(int lost_after, double gyro_deg, int contradictions, double accel_mps2 = 0.0) {
  tracking::TrackingOptions o;
  o.lost_after_failures = lost_after;
  o.lost_gyro_disagreement_deg = gyro_deg;
  o.lost_gyro_contradictions = contradictions;
  o.lost_accel_mps2 = accel_mps2;
  return o;
}

/// Frame k (50 ms apart); `carried`: the IMU modes' window carried it (a window state).
FrameRecord frame(int k, bool passed, bool carried = false) {
  FrameRecord r;
  r.t_ns = 1000000000LL + k * 50000000LL;
  r.aligned = k > 0;
  r.alignment.self_check_passed = passed;
  if (carried) r.state = imu::NavState{};
  return r;
}

TEST(LossMonitor, ConsecutiveFailuresLoseTheEstimateFromTheFirstUntilTrackedAgain) {
  LossMonitor m(lossOptions(3, 2.0, 3));
  std::vector<FrameRecord> r;
  // Frame 0 is a first frame; 2-3 fail (two: not lost); 5-9 fail; 10 tracks again.
  for (int k = 0; k <= 11; ++k) r.push_back(frame(k, !(k == 2 || k == 3 || (k >= 5 && k <= 9))));
  for (FrameRecord& x : r) m.update(&x);
  for (int k = 0; k <= 11; ++k) {
    const bool lost = k >= 7 && k <= 9;  // declared at the third failure (7), until frame 10 tracks
    EXPECT_EQ(r[k].status == TrackingStatus::kLost, lost) << k;
    EXPECT_EQ(r[k].lost_since_ns >= 0, k == 7) << k;
  }
  EXPECT_EQ(r[7].lost_since_ns, r[5].t_ns);  // its first symptom
  EXPECT_EQ(r[7].lost_reason, "3 consecutive self-check failures");
}

TEST(LossMonitor, ThreeFramesTheGyroscopeContradictsAmongTenAreALoss) {
  // Frozen images: frames 3, 5 and 6 align (self check passed) but rotate
  // 2.5 deg less than the gyroscope; frame 4 disagrees by 1.9 deg (under
  // the threshold). Lost from frame 3 at the third contradiction (6) until a
  // tracked frame finds fewer than 3 in its window of 10: frame 13, when
  // frame 3 has left it.
  const auto run = [](double threshold, int contradictions, double nan_or_disagreement) {
    LossMonitor m(lossOptions(10, threshold, contradictions));
    std::vector<FrameRecord> r;
    for (int k = 0; k <= 15; ++k) {
      r.push_back(frame(k, true));
      r.back().gyro_disagreement_deg = k == 3 || k == 5 || k == 6 ? nan_or_disagreement : (k == 4 ? 1.9 : 0.2);
    }
    for (FrameRecord& x : r) m.update(&x);
    return r;
  };
  const std::vector<FrameRecord> r = run(2.0, 3, 2.5);
  for (int k = 0; k <= 15; ++k) {
    EXPECT_EQ(r[k].status == TrackingStatus::kLost, k >= 6 && k <= 12) << k;
    EXPECT_EQ(r[k].lost_since_ns >= 0, k == 6) << k;
  }
  EXPECT_EQ(r[6].lost_since_ns, r[3].t_ns);
  EXPECT_EQ(r[6].lost_reason, "the gyroscope contradicts 3 of the last 6 frames' rotation by over 2.0 deg");
  // Off, or no gyroscope reading (NaN): nothing is lost.
  for (const auto& none : {run(2.0, 0, 2.5), run(2.0, 3, std::numeric_limits<double>::quiet_NaN())})
    for (const FrameRecord& x : none) EXPECT_EQ(x.status, TrackingStatus::kOk) << x.t_ns;
}

TEST(LossMonitor, ScatteredFailuresAreEvidenceWhereTheImuDidNotCarryTheFrame) {
  // Frames 2 and 5 fail the self check, frame 7 rotates 2.5 deg off the
  // gyroscope: three suspects among ten. Without the IMU a failed frame's
  // pose is a guess, so that is a loss; with the IMU, which carries failed
  // frames, one contradiction is none; in an IMU gap over frames 1-6 the
  // IMU modes carry nothing, as the visual modes.
  const auto run = [](const std::function<bool(int)>& carried) {
    LossMonitor m(lossOptions(10, 2.0, 3));
    std::vector<FrameRecord> r;
    for (int k = 0; k <= 16; ++k) {
      r.push_back(frame(k, !(k == 2 || k == 5), carried(k)));
      r.back().gyro_disagreement_deg = k == 7 ? 2.5 : 0.2;
    }
    for (FrameRecord& x : r) m.update(&x);
    return r;
  };
  const std::vector<FrameRecord> visual = run([](int) { return false; }), inertial = run([](int) { return true; }),
                                 gap = run([](int k) { return k < 1 || k > 6; });
  // Lost at 7 (since 2); frame 8 tracks but its window (frames 0-8 aligned
  // from 1) still holds 3 suspects, and so on until frame 12, whose window
  // (3-12) holds 2.
  for (int k = 0; k <= 16; ++k) {
    EXPECT_EQ(visual[k].status == TrackingStatus::kLost, k >= 7 && k <= 11) << k;
    EXPECT_EQ(inertial[k].status, TrackingStatus::kOk) << k;
    EXPECT_EQ(gap[k].status, visual[k].status) << k;
  }
  EXPECT_EQ(visual[7].lost_since_ns, visual[2].t_ns);
  EXPECT_EQ(visual[7].lost_reason, "3 of the last 7 frames failed the self check or their rotation is over 2.0 deg from the gyroscope's");
}

TEST(LossMonitor, AFrozenImageIsLostAtOnceWithoutTheImuAndAFailureWithIt) {
  // Frames 2-5 repeat frame 1's image and align to it (self check passed).
  const auto run = [](bool imu) {
    LossMonitor m(lossOptions(3, 2.0, 3));
    std::vector<FrameRecord> r;
    for (int k = 0; k <= 7; ++k) {
      r.push_back(frame(k, true, imu));
      r.back().frozen_image = k >= 2 && k <= 5;
    }
    for (FrameRecord& x : r) m.update(&x);
    return r;
  };
  const std::vector<FrameRecord> visual = run(false), inertial = run(true);
  for (int k = 0; k <= 7; ++k) {
    EXPECT_EQ(visual[k].status == TrackingStatus::kLost, k >= 2 && k <= 5) << k;
    EXPECT_EQ(inertial[k].status == TrackingStatus::kLost, k >= 4 && k <= 5) << k;  // the third "failure"
  }
  EXPECT_EQ(visual[2].lost_reason, "the image repeats the previous frame's to the last pixel (a stalled or blank camera)");
  EXPECT_EQ(inertial[4].lost_since_ns, inertial[2].t_ns);
}

TEST(LossMonitor, ANonFinitePoseIsLostAtOnce) {
  LossMonitor m(lossOptions(10, 2.0, 3));
  FrameRecord ok = frame(1, true), bad = frame(2, true), again = frame(3, true);
  bad.T_w_b = geometry::SE3(geometry::SO3(), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  m.update(&ok);
  m.update(&bad);
  m.update(&again);
  EXPECT_EQ(ok.status, TrackingStatus::kOk);
  EXPECT_EQ(bad.status, TrackingStatus::kLost);
  EXPECT_EQ(bad.lost_since_ns, bad.t_ns);
  EXPECT_EQ(bad.lost_reason, "non-finite pose");
  EXPECT_EQ(again.status, TrackingStatus::kOk);
}

TEST(LossMonitor, AStepNoRigCouldAccelerateToIsLostUntilThePosesAreSmoothAgain) {
  // Frame 4 aligned 0.5 m off (in another basin) and stays there: the step
  // implies 0.5 m / (50 ms)^2 = 200 m/s^2 into frame 4 and as much out of it
  // (frame 5's second difference), then the motion is smooth again.
  const auto run = [](double accel_mps2) {
    LossMonitor m(lossOptions(10, 2.0, 3, accel_mps2));
    std::vector<FrameRecord> r;
    for (int k = 0; k <= 7; ++k) {
      r.push_back(frame(k, true));
      r.back().implied_accel_mps2 = k == 4 || k == 5 ? 200.0 : 1.0;
    }
    for (FrameRecord& x : r) m.update(&x);
    return r;
  };
  const std::vector<FrameRecord> r = run(100.0);
  for (int k = 0; k <= 7; ++k) {
    EXPECT_EQ(r[k].status == TrackingStatus::kLost, k == 4 || k == 5) << k;
    EXPECT_EQ(r[k].lost_since_ns >= 0, k == 4) << k;
  }
  EXPECT_EQ(r[4].lost_reason, "the pose's step implies an acceleration of 200 m/s^2, over 100");
  for (const auto& none : {run(0.0), run(250.0)})  // off, or a threshold above the step
    for (const FrameRecord& x : none) EXPECT_EQ(x.status, TrackingStatus::kOk) << x.t_ns;
}

TEST(LossMonitor, AnEstimateRunningAwayAtASteadySpeedIsLost) {
  // Frames 3-6 move 6 m per 50 ms (120 m/s, the run-away of a 2 s IMU gap
  // in fast flight): no acceleration after the first step, yet lost until
  // a plausible step.
  const auto run = [](double speed_mps) {
    tracking::TrackingOptions o = lossOptions(10, 2.0, 3, 0.0);
    o.lost_speed_mps = speed_mps;
    LossMonitor m(o);
    std::vector<FrameRecord> r;
    for (int k = 0; k <= 8; ++k) {
      r.push_back(frame(k, true));
      r.back().implied_speed_mps = k >= 3 && k <= 6 ? 120.0 : 2.0;
    }
    for (FrameRecord& x : r) m.update(&x);
    return r;
  };
  const std::vector<FrameRecord> r = run(100.0);
  for (int k = 0; k <= 8; ++k) EXPECT_EQ(r[k].status == TrackingStatus::kLost, k >= 3 && k <= 6) << k;
  EXPECT_EQ(r[3].lost_reason, "the pose's step implies a speed of 120 m/s, over 100");
  for (const auto& none : {run(0.0), run(150.0)})  // off, or a bound above the speed
    for (const FrameRecord& x : none) EXPECT_EQ(x.status, TrackingStatus::kOk) << x.t_ns;
}

TEST(LossMonitor, AStepTheAccelerometerDoesNotExplainIsLostWithABoundThatGrowsWithTheInterval) {
  // Frame 4 lands 0.3 m off and stays (in another basin): frame 4 lies 0.3 m
  // from the accelerometer's prediction, and frame 5, predicted with the
  // velocity that step implies, as far again; then the poses are consistent.
  // The bound is 0.05 m + 1 m/s^2 * dt * (dt + dt0) / 2: 0.0525 m at 20 Hz,
  // 0.69 m with 0.8 s between frames (K = 15), where 0.3 m is within it.
  const auto run = [](std::int64_t period_ns, double disagreement_m) {
    tracking::TrackingOptions o = lossOptions(10, 2.0, 3, 0.0);
    o.lost_accel_disagreement_m = disagreement_m;
    o.lost_accel_disagreement_mps2 = 1.0;
    LossMonitor m(o);
    std::vector<FrameRecord> r;
    for (int k = 0; k <= 8; ++k) {
      r.push_back(frame(k, true));
      r.back().t_ns = 1000000000LL + k * period_ns;
      r.back().accel_disagreement_m = k == 4 || k == 5 ? 0.3 : (k == 2 ? 0.0524 : 0.002);
    }
    for (FrameRecord& x : r) m.update(&x);
    return r;
  };
  const std::vector<FrameRecord> r = run(50000000LL, 0.05);
  for (int k = 0; k <= 8; ++k) {
    EXPECT_EQ(r[k].status == TrackingStatus::kLost, k == 4 || k == 5) << k;
    EXPECT_EQ(r[k].lost_since_ns >= 0, k == 4) << k;
  }
  EXPECT_EQ(r[4].lost_reason, "the pose lies 0.30 m from the accelerometer's prediction, over 0.05");
  for (const auto& none : {run(50000000LL, 0.0), run(800000000LL, 0.05)})  // off, or frames 0.8 s apart
    for (const FrameRecord& x : none) EXPECT_EQ(x.status, TrackingStatus::kOk) << x.t_ns;
}

}  // namespace
}  // namespace edgevio::pipeline
