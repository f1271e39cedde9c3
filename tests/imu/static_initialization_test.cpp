// Initial attitude and gyro bias from the first IMU window (METHOD.md §5,
// `imu::staticInitialization`), on hand-made samples whose truth is known
// in closed form: a rig at rest, a rig shaken along a line, and free fall;
// and the gyroscope's rotation between two times, which no gap may span.
#include "edgevio/imu/gyro_integration.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <iterator>
#include <random>

namespace edgevio::imu {
namespace {

using geometry::SO3;

constexpr double kG = 9.81;
constexpr std::int64_t kDtNs = 5000000;  // 200 Hz

/// Angle between the world z axis and the "up" the initial attitude assumes
/// for a body whose true attitude is R_true: R_w_b · R_trueᵀ · z.
double tiltErrorDeg(const SO3& R_w_b, const SO3& R_true) {
  const Vec3 up = R_w_b * (R_true.inverse() * Vec3::UnitZ());
  return std::acos(std::clamp(up.z(), -1.0, 1.0)) * 180.0 / kPi;
}

/// Samples of a rig with constant attitude R, constant gyro bias, and world
/// acceleration a_w(t); white noise of the given densities at 200 Hz.
std::vector<imu::ImuSample> samples(const SO3& R, const Vec3& gyro_bias, double seconds,
                                   const std::function<Vec3(double)>& a_w, double accel_noise, double gyro_noise) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> n01;
  std::vector<imu::ImuSample> out;
  for (std::int64_t t = 0; t <= static_cast<std::int64_t>(seconds * 1e9); t += kDtNs) {
    imu::ImuSample s;
    s.t_ns = t;
    s.accel = R.inverse() * (a_w(static_cast<double>(t) * 1e-9) + Vec3(0, 0, kG)) +
              accel_noise * Vec3(n01(rng), n01(rng), n01(rng));
    s.gyro = gyro_bias + gyro_noise * Vec3(n01(rng), n01(rng), n01(rng));
    out.push_back(s);
  }
  return out;
}

const SO3 kTilted = SO3::exp(Vec3(0.4, -1.2, 0.7));  // body x axis nearly up, like EuRoC's MAV on the ground

TEST(StaticInitialization, AtRestFindsGravityAndGyroBias) {
  const Vec3 bias(0.002, -0.02, 0.08);
  // Noise per sample 0.02 m/s² and 2e-3 rad/s (ADIS16448-like at 200 Hz): over
  // 200 samples the means are good to 0.02/√200 = 1.4e-3 m/s² (0.008 deg of
  // tilt) and 1.4e-4 rad/s; the bounds are five times that.
  const auto imu = samples(kTilted, bias, 1.0, [](double) { return Vec3::Zero(); }, 0.02, 2e-3);
  const StaticInit s = staticInitialization(imu, 0, 1.0, 0.1, 0.25, 0.05);
  EXPECT_TRUE(s.is_static);
  EXPECT_LT(tiltErrorDeg(s.R_w_b, kTilted), 0.04);
  EXPECT_LT((s.gyro_bias - bias).norm(), 7e-4);
  // Yaw is the gauge and stays at zero: the rotation is the smallest one.
  EXPECT_NEAR((s.R_w_b * (kTilted.inverse() * Vec3::UnitZ())).z(), 1.0, 1e-6);
}

TEST(StaticInitialization, InMotionStillGivesAnApproximateUpButNoGyroBias) {
  // Shaken along world x and z with amplitude 0.15 m at 0.8 Hz (peak
  // acceleration 3.8 m/s²). Over a window of T = 1 s the mean world
  // acceleration is Δv / T, at most d = 2·0.15·2π·0.8 = 1.5 m/s² per axis: the
  // mean specific force tilts by at most atan(d / (g − d)) ≈ 10 deg.
  const double w = 2 * kPi * 0.8, amp = 0.15;
  const auto shake = [&](double t) { return Vec3(-amp * w * w * std::sin(w * t), 0, -amp * w * w * std::sin(w * t + 1.0)); };
  const auto imu = samples(kTilted, Vec3(0.0, 0.0, 0.08), 1.0, shake, 0.02, 2e-3);
  const StaticInit s = staticInitialization(imu, 0, 1.0, 0.1, 0.25, 0.05);
  EXPECT_FALSE(s.is_static);
  EXPECT_EQ(s.gyro_bias, Vec3::Zero());
  const double d = 2 * amp * w / 1.0;
  const double bound_deg = std::atan(d / (kG - d)) * 180.0 / kPi;
  EXPECT_LT(tiltErrorDeg(s.R_w_b, kTilted), bound_deg);
  // A level start would be ~70 deg off for this rig.
  EXPECT_GT(tiltErrorDeg(SO3(), kTilted), 60.0);
}

TEST(StaticInitialization, FreeFallGivesNoAttitude) {
  const auto imu = samples(kTilted, Vec3::Zero(), 1.0, [](double) { return Vec3(0, 0, -kG); }, 0.02, 2e-3);
  const StaticInit s = staticInitialization(imu, 0, 1.0, 0.1, 0.25, 0.05);
  EXPECT_FALSE(s.is_static);
  EXPECT_EQ(s.R_w_b.matrix(), Mat3::Identity());
}

TEST(IntegrateGyro, ExactForAConstantRateAndRefusedAcrossAGap) {
  // 1 rad/s about z at 200 Hz: 0.3 rad over 0.3 s (the midpoint rule is
  // exact for a constant rate). Without the readings of 0.1-0.2 s the rate
  // interpolated across the gap would still give 0.3 rad, but only because
  // the rate happens to be constant: a gap longer than max_gap_s gives none.
  std::vector<ImuSample> imu;
  for (std::int64_t t = 0; t <= 400000000; t += kDtNs) imu.push_back({t, Vec3(0, 0, 1), Vec3(0, 0, kG)});
  SO3 R;
  ASSERT_TRUE(integrateGyro(imu, 50000000, 350000000, Vec3::Zero(), 0.05, &R));
  EXPECT_NEAR(R.log().z(), 0.3, 1e-12);
  std::vector<ImuSample> gap;
  std::copy_if(imu.begin(), imu.end(), std::back_inserter(gap),
               [](const ImuSample& s) { return s.t_ns <= 100000000 || s.t_ns >= 200000000; });
  EXPECT_FALSE(integrateGyro(gap, 50000000, 350000000, Vec3::Zero(), 0.05, &R));
  EXPECT_TRUE(R.log().isZero());
  ASSERT_TRUE(integrateGyro(gap, 50000000, 350000000, Vec3::Zero(), 0.15, &R));  // a gap under max_gap_s is bridged
  EXPECT_NEAR(R.log().z(), 0.3, 1e-12);
  EXPECT_TRUE(integrateGyro(gap, 210000000, 350000000, Vec3::Zero(), 0.05, &R));  // after the gap: covered again
}

}  // namespace
}  // namespace edgevio::imu
