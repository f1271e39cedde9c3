// The IMU-rate pose (imu/imu_rate.h) on motions whose midpoint integration is
// exact: a constant rotation rate at rest (each step's rotation is exp of the
// rate, and the rotated specific force is gravity at every reading) and a
// constant acceleration without rotation (the midpoint rule integrates a
// constant exactly). What is left is rounding: tolerances of 1e-9.
#include "edgevio/imu/imu_rate.h"

#include <gtest/gtest.h>

namespace edgevio::imu {
namespace {

using geometry::SO3;

constexpr std::int64_t kStepNs = 5000000;  // 200 Hz
constexpr double kTol = 1e-9;

// At rest at p0, turning at a constant body rate w from R0.
struct Turning {
  SO3 R0 = SO3::exp(Vec3(0.3, -0.2, 1.0));
  Vec3 w = Vec3(0.5, -1.2, 2.0);  // rad/s
  Vec3 p0 = Vec3(1.0, 2.0, 3.0);
  SO3 R(double t) const { return R0 * SO3::exp(w * t); }
  ImuSample reading(std::int64_t t_ns) const {
    ImuSample s;
    s.t_ns = t_ns;
    s.gyro = w;
    s.accel = R(t_ns * 1e-9).inverse() * gravity();  // at rest the accelerometer reads gravity's reaction
    return s;
  }
  NavState state(double t) const {
    NavState x;
    x.R_w_b = R(t);
    x.p_w = p0;
    return x;
  }
};

// Level, accelerating at a constant a from p0 with v0.
struct Accelerating {
  Vec3 a = Vec3(1.5, -0.5, 0.25), v0 = Vec3(2.0, 0.0, -1.0), p0 = Vec3(-1.0, 0.5, 2.0);
  ImuSample reading(std::int64_t t_ns) const {
    ImuSample s;
    s.t_ns = t_ns;
    s.accel = a + gravity();
    return s;
  }
  NavState state(double t) const {
    NavState x;
    x.p_w = p0 + v0 * t + 0.5 * a * t * t;
    x.v_w = v0 + a * t;
    return x;
  }
};

TEST(ImuRate, ATurnAtRestIsFollowedExactly) {
  const Turning m;
  ImuRatePropagator prop(0.05);
  prop.setEstimate(0, m.state(0));
  for (int k = 0; k <= 200; ++k) {
    const std::optional<NavState> x = prop.propagate(m.reading(k * kStepNs));
    if (k == 0) {
      EXPECT_FALSE(x) << "a reading at the estimate's own time has nothing to propagate";
      continue;
    }
    ASSERT_TRUE(x) << k;
    const double t = k * kStepNs * 1e-9;
    EXPECT_LT((m.R(t).inverse() * x->R_w_b).log().norm(), kTol) << t;
    EXPECT_LT((x->p_w - m.p0).norm(), kTol) << t;
    EXPECT_LT(x->v_w.norm(), kTol) << t;
  }
}

TEST(ImuRate, AConstantAccelerationFollowsItsParabola) {
  const Accelerating m;
  ImuRatePropagator prop(0.05);
  prop.propagate(m.reading(0));
  // An estimate between two readings: the first step starts from the reading interpolated at its time.
  const std::int64_t t_est = 2500000;
  prop.setEstimate(t_est, m.state(t_est * 1e-9));
  for (int k = 1; k <= 200; ++k) {
    const std::optional<NavState> x = prop.propagate(m.reading(k * kStepNs));
    ASSERT_TRUE(x) << k;
    const NavState truth = m.state(k * kStepNs * 1e-9);
    EXPECT_LT((x->p_w - truth.p_w).norm(), kTol) << k;
    EXPECT_LT((x->v_w - truth.v_w).norm(), kTol) << k;
  }
}

TEST(ImuRate, ALateEstimateTakesOverFromItsOwnTime) {
  // In real time the estimate of a frame arrives after later readings: they
  // are integrated again from it.
  const Accelerating m;
  ImuRatePropagator prop(0.05);
  prop.setEstimate(0, m.state(0));
  for (int k = 0; k <= 100; ++k) prop.propagate(m.reading(k * kStepNs));
  const double t_new = 0.3025;  // between readings 60 and 61
  NavState newer = m.state(t_new);
  const Vec3 dp(1.0, 0.0, 0.0), dv(0.2, -0.1, 0.0);  // what the window moved the state by
  newer.p_w += dp;
  newer.v_w += dv;
  prop.setEstimate(static_cast<std::int64_t>(t_new * 1e9), newer);
  EXPECT_EQ(prop.estimateTime(), static_cast<std::int64_t>(t_new * 1e9));
  const std::optional<NavState> x = prop.propagate(m.reading(101 * kStepNs));
  ASSERT_TRUE(x);
  const double t = 101 * kStepNs * 1e-9;
  EXPECT_LT((x->p_w - (m.state(t).p_w + dp + dv * (t - t_new))).norm(), kTol);
  EXPECT_LT((x->v_w - (m.state(t).v_w + dv)).norm(), kTol);
  // An older estimate than the newest changes nothing.
  prop.setEstimate(0, m.state(0));
  EXPECT_EQ(prop.estimateTime(), static_cast<std::int64_t>(t_new * 1e9));
}

TEST(ImuRate, WithoutNewEstimatesTheKeptReadingsStayBounded) {
  // A stalled tracker: one estimate, then a minute of readings. The poses go
  // on from the estimate, and at most kKeptSeconds + 1 s of readings (+ the
  // one before) wait for a later estimate.
  const Accelerating m;
  ImuRatePropagator prop(0.05);
  prop.setEstimate(0, m.state(0));
  prop.propagate(m.reading(0));
  const int readings = static_cast<int>(60.0 / (kStepNs * 1e-9));
  const std::size_t bound = static_cast<std::size_t>((ImuRatePropagator::kKeptSeconds + 1.0) / (kStepNs * 1e-9)) + 2;
  std::size_t most = 0;
  for (int k = 1; k <= readings; ++k) {
    ASSERT_TRUE(prop.propagate(m.reading(k * kStepNs))) << k;
    most = std::max(most, prop.keptReadings());
  }
  EXPECT_LE(most, bound);
  EXPECT_GT(most, bound - 10);  // it does keep them
  // An estimate 5 s behind the newest reading still takes over.
  const std::int64_t t_new = (readings - 1000) * kStepNs + kStepNs / 2;
  prop.setEstimate(t_new, m.state(t_new * 1e-9));
  const std::optional<NavState> x = prop.propagate(m.reading((readings + 1) * kStepNs));
  ASSERT_TRUE(x);
  EXPECT_LT((x->p_w - m.state((readings + 1) * kStepNs * 1e-9).p_w).norm(), 1e-6);
}

TEST(ImuRate, NothingBeforeAnEstimateNorAcrossAGap) {
  const Accelerating m;
  ImuRatePropagator prop(0.05);
  for (int k = 0; k < 10; ++k) EXPECT_FALSE(prop.propagate(m.reading(k * kStepNs))) << "no estimate yet";
  prop.setEstimate(9 * kStepNs, m.state(9 * kStepNs * 1e-9));
  EXPECT_TRUE(prop.propagate(m.reading(10 * kStepNs)));
  // 0.1 s without readings, twice the largest gap integrated across.
  EXPECT_FALSE(prop.propagate(m.reading(30 * kStepNs)));
  EXPECT_FALSE(prop.propagate(m.reading(31 * kStepNs))) << "the propagation stays broken until a newer estimate";
  EXPECT_FALSE(prop.propagate(m.reading(31 * kStepNs))) << "a reading out of order is ignored";
  prop.setEstimate(31 * kStepNs, m.state(31 * kStepNs * 1e-9));
  const std::optional<NavState> x = prop.propagate(m.reading(32 * kStepNs));
  ASSERT_TRUE(x);
  EXPECT_LT((x->p_w - m.state(32 * kStepNs * 1e-9).p_w).norm(), kTol);
}

}  // namespace
}  // namespace edgevio::imu
