// Noise off, the synthetic IMU integrated over any 1 s window must reproduce
// the ground-truth motion to under 1 cm and 0.1 deg (issue #4).
#include "edgevio/sim/imu_synth.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "common/test_support.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::sim {
namespace {

using geometry::SO3;

struct WindowError {
  double position_m = 0.0, rotation_deg = 0.0;
};

/// Integrates IMU samples [i0, i0 + n] from the true state at i0 with a
/// second-order scheme (midpoint rotation, trapezoidal acceleration) and
/// returns the error at the end against the spline.
WindowError integrateWindow(const SplineTrajectory& s, const SynthesizedImu& imu, std::size_t i0, std::size_t n) {
  const KinematicState start = s.evaluate(imu.samples[i0].t_ns);
  SO3 R = start.T_w_b.so3();
  Vec3 p = start.T_w_b.translation(), v = start.v_w;
  const Vec3 g(0, 0, kGravity);
  for (std::size_t k = i0; k < i0 + n; ++k) {
    const auto& a = imu.samples[k];
    const auto& b = imu.samples[k + 1];
    const double dt = static_cast<double>(b.t_ns - a.t_ns) * 1e-9;
    const SO3 R_next = R * SO3::exp(0.5 * (a.gyro + b.gyro) * dt);
    const Vec3 acc0 = R * a.accel - g, acc1 = R_next * b.accel - g;
    p += v * dt + (acc0 / 3.0 + acc1 / 6.0) * dt * dt;  // exact for linearly varying acceleration
    v += 0.5 * (acc0 + acc1) * dt;
    R = R_next;
  }
  const KinematicState end = s.evaluate(imu.samples[i0 + n].t_ns);
  return {(p - end.T_w_b.translation()).norm(), geometry::angle(R.inverse() * end.T_w_b.so3()) * kRadToDeg};
}

void checkAllWindows(const SplineTrajectory& s, const std::string& what) {
  ImuSynthOptions o;
  o.noise = false;
  const SynthesizedImu imu = synthesizeImu(s, s.beginNs(), s.endNs(), o, 1);
  double worst_p = 0, worst_r = 0;
  for (std::size_t i0 = 0; i0 + 200 < imu.samples.size(); i0 += 50) {
    const WindowError e = integrateWindow(s, imu, i0, 200);  // 1 s at 200 Hz
    worst_p = std::max(worst_p, e.position_m);
    worst_r = std::max(worst_r, e.rotation_deg);
  }
  EXPECT_LT(worst_p, 0.01) << what;
  EXPECT_LT(worst_r, 0.1) << what;
  ::testing::Test::RecordProperty(what + "_worst_position_m", std::to_string(worst_p));
  ::testing::Test::RecordProperty(what + "_worst_rotation_deg", std::to_string(worst_r));
  std::printf("%s: worst 1 s window %.2e m, %.2e deg\n", what.c_str(), worst_p, worst_r);
}

TEST(ImuSynth, NoiseFreeIntegrationMatchesScenarios) {
  const camera::StereoRig rig = io::eurocDefaultRig();
  for (const std::string name : {"figure8", "aggressive", "throw"}) {
    const io::Trajectory samples = scenarioSamples(name, 16.0, 1.0, rig.T_b_c[0]);
    checkAllWindows(fitSpline(samples, kScenarioStartNs, kScenarioStartNs + 15000000000LL, 0.05, 0.1, name), name);
  }
}

TEST(ImuSynth, NoiseFreeIntegrationMatchesARealTrajectory) {
  EDGEVIO_REQUIRE_SHARED_DATA("trajectories/uzhfpv/indoor_forward_3_groundtruth_tum.txt");
  const io::Trajectory samples = io::readTrajectory(data_path);
  const std::int64_t t0 = samples.front().t_ns + 10000000000LL;
  checkAllWindows(fitSpline(samples, t0, t0 + 15000000000LL, 0.05, 0.1, data_path), "uzhfpv_indoor_forward_3");
}

TEST(ImuSynth, AtRestReadsGravityUpAndNoRotation) {
  const SplineTrajectory s(0, 50000000, std::vector<geometry::SE3>(10, geometry::SE3()));
  ImuSynthOptions o;
  o.noise = false;
  const SynthesizedImu imu = synthesizeImu(s, s.beginNs(), s.endNs(), o, 1);
  for (const auto& m : imu.samples) {
    EXPECT_LT((m.accel - Vec3(0, 0, 9.81)).norm(), 1e-12);
    EXPECT_LT(m.gyro.norm(), 1e-12);
  }
}

TEST(ImuSynth, NoiseHasTheConfiguredDensity) {
  const SplineTrajectory s(0, 50000000, std::vector<geometry::SE3>(2003, geometry::SE3()));  // 100 s at rest
  ImuSynthOptions o;
  o.initial_gyro_bias_sigma = o.initial_accel_bias_sigma = 0.0;
  o.densities.gyro_random_walk = o.densities.accel_random_walk = 1e-12;  // isolate the white noise
  const SynthesizedImu imu = synthesizeImu(s, s.beginNs(), s.endNs(), o, 7);
  double sg = 0, sa = 0;
  for (const auto& m : imu.samples) {
    sg += m.gyro.squaredNorm();
    sa += (m.accel - Vec3(0, 0, 9.81)).squaredNorm();
  }
  const double n = 3.0 * static_cast<double>(imu.samples.size());
  // σ_discrete = σ_c · √rate; with 60000 draws the sample std is within ~1 % (3σ).
  EXPECT_NEAR(std::sqrt(sg / n), o.densities.gyro_noise_density * std::sqrt(200.0), 0.015 * o.densities.gyro_noise_density * std::sqrt(200.0));
  EXPECT_NEAR(std::sqrt(sa / n), o.densities.accel_noise_density * std::sqrt(200.0), 0.015 * o.densities.accel_noise_density * std::sqrt(200.0));
}

}  // namespace
}  // namespace edgevio::sim
