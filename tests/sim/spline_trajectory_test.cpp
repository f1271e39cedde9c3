// The spline's analytic derivatives against numeric differentiation of its
// own pose, and the scenarios' promised motion properties.
#include "edgevio/sim/spline_trajectory.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::sim {
namespace {

using geometry::SE3;
using geometry::SO3;

SplineTrajectory scenarioSpline(const std::string& name, double seconds) {
  const camera::StereoRig rig = io::eurocDefaultRig();
  const io::Trajectory samples = scenarioSamples(name, seconds + 1.0, 1.0, rig.T_b_c[0]);
  return fitSpline(samples, kScenarioStartNs, kScenarioStartNs + static_cast<std::int64_t>(seconds * 1e9), 0.05, 0.1, name);
}

TEST(SplineTrajectory, DerivativesMatchNumericDifferentiation) {
  const SplineTrajectory s = scenarioSpline("aggressive", 6.0);
  const std::int64_t h = 100000;  // 0.1 ms
  for (std::int64_t t = s.beginNs() + 123456789; t < s.endNs() - h; t += 271828182) {
    const KinematicState k = s.evaluate(t);
    const KinematicState kp = s.evaluate(t + h), km = s.evaluate(t - h);
    const double dt = 1e-4;
    const Vec3 v_num = (kp.T_w_b.translation() - km.T_w_b.translation()) / (2 * dt);
    const Vec3 a_num = (kp.v_w - km.v_w) / (2 * dt);
    // R⁻¹Ṙ = hat(ω): ω ≈ log(R(t−h)⁻¹ R(t+h)) / 2h
    const Vec3 w_num = (km.T_w_b.so3().inverse() * kp.T_w_b.so3()).log() / (2 * dt);
    // Central differences have O(h²) error; with h = 0.1 ms and jerk < 1e3 m/s³ that is < 1e-5.
    EXPECT_LT((k.v_w - v_num).norm(), 1e-5 * std::max(1.0, v_num.norm()));
    EXPECT_LT((k.a_w - a_num).norm(), 1e-4 * std::max(1.0, a_num.norm()));
    EXPECT_LT((k.omega_b - w_num).norm(), 1e-5 * std::max(1.0, w_num.norm()));
  }
}

TEST(SplineTrajectory, ReproducesASmoothTrajectoryClosely) {
  // Control points on a slow circle: the B-spline approximates it to O(a·dt²/6).
  std::vector<SE3> cps;
  const double dt = 0.05, r = 1.0, w = 0.5;
  for (int k = 0; k < 60; ++k) {
    const double t = (k - 1) * dt;
    cps.emplace_back(SO3::exp(Vec3(0, 0, w * t)), Vec3(r * std::cos(w * t), r * std::sin(w * t), 0));
  }
  const SplineTrajectory s(0, 50000000, cps);
  for (double t = 0.1; t < 2.5; t += 0.13) {
    const KinematicState k = s.evaluate(static_cast<std::int64_t>(t * 1e9));
    const double bound = r * w * w * dt * dt / 6.0 * 1.01;
    EXPECT_LT((k.T_w_b.translation() - Vec3(r * std::cos(w * t), r * std::sin(w * t), 0)).norm(), bound);
    EXPECT_NEAR(k.omega_b.z(), w, 1e-9);  // constant-rate rotation is reproduced exactly
  }
}

double peak(const SplineTrajectory& s, bool angular) {
  double m = 0.0;
  for (std::int64_t t = s.beginNs(); t <= s.endNs(); t += 5000000) {
    const KinematicState k = s.evaluate(t);
    m = std::max(m, angular ? k.omega_b.norm() : k.a_w.norm());
  }
  return m;
}

TEST(Scenarios, AggressiveReachesTheRatesItPromises) {
  const SplineTrajectory s = scenarioSpline("aggressive", 20.0);
  EXPECT_GE(peak(s, true), 5.0);         // rad/s
  EXPECT_GE(peak(s, false), 2.0 * 9.81);  // m/s²
}

TEST(Scenarios, EveryScenarioStartsAtRestWithTheCameraLevel) {
  const camera::StereoRig rig = io::eurocDefaultRig();
  for (const std::string& name : scenarioNames()) {
    const SplineTrajectory s = scenarioSpline(name, 3.0);
    for (std::int64_t t = s.beginNs() + 100000000; t < s.beginNs() + 800000000; t += 100000000) {
      const KinematicState k = s.evaluate(t);
      EXPECT_LT(k.v_w.norm(), 1e-9) << name;
      EXPECT_LT(k.omega_b.norm(), 1e-9) << name;
    }
    // Camera y axis (down in the image) points down in the world at the start.
    const SO3 R_w_c = s.pose(s.beginNs()).so3() * rig.T_b_c[0].so3();
    EXPECT_GT((R_w_c * Vec3::UnitY()).dot(-Vec3::UnitZ()), 0.99) << name;
  }
}

TEST(Scenarios, ThrowHasFreeFlight) {
  // During a flight the rig is in free fall: |a + g| ≈ 0 (the accelerometer reads ~0).
  const SplineTrajectory s = scenarioSpline("throw", 12.0);
  int free_fall = 0;
  for (std::int64_t t = s.beginNs(); t <= s.endNs(); t += 10000000) {
    const KinematicState k = s.evaluate(t);
    if ((k.a_w + Vec3(0, 0, 9.81)).norm() < 1.0) ++free_fall;
  }
  EXPECT_GT(free_fall, 60);  // several flights of 0.7 s, sampled at 100 Hz
}

// removePositionSteps: a scenario is smooth (accelerations of several g, but
// continuous), so the median of an increment's ten neighbours is its own
// velocity up to jerk·(5Δt)² ≈ 1e-3 m/s, far inside 50 m/s²·Δt = 0.25 m/s.
TEST(RemovePositionSteps, KeepsEverySmoothScenarioAsItIs) {
  const camera::StereoRig rig = io::eurocDefaultRig();
  for (const std::string& name : scenarioNames()) {
    io::Trajectory samples = scenarioSamples(name, 20.0, 1.0, rig.T_b_c[0]);
    const io::Trajectory original = samples;
    EXPECT_EQ(removePositionSteps(samples, 50.0, 1.0), 0) << name;
    for (std::size_t i = 0; i < samples.size(); ++i)
      ASSERT_EQ(samples[i].T_w_b.translation(), original[i].T_w_b.translation()) << name << " sample " << i;
  }
}

// A 13 cm one-sample spike (as at 45 s in EuRoC MH_04's ground truth) and a
// 2 cm step (as at 71.3 s) on a smooth path. The spike is two replaced
// increments and its peak is never averaged in, so it leaves no trace; the
// step is one replaced increment, and its offset returns as the boxcar average
// of a step: a ramp from 0 to s over spread_s, i.e. at most |s|·Δt/spread_s
// per sample. Elsewhere the only error is the median's: the spike's other
// increment is one of the ten neighbours and shifts the median by up to one
// neighbour, |a|·Δt in velocity, so |a|·Δt² in position per replaced increment;
// figure8 has |a| < 2 m/s², so < 1e-4 m for the three.
TEST(RemovePositionSteps, RemovesASpikeAndTurnsAStepIntoARamp) {
  const camera::StereoRig rig = io::eurocDefaultRig();
  const io::Trajectory smooth = scenarioSamples("figure8", 20.0, 1.0, rig.T_b_c[0]);
  const auto at = [&](double seconds) {
    const std::int64_t t = smooth.front().t_ns + static_cast<std::int64_t>(seconds * 1e9);
    return static_cast<std::size_t>(std::lower_bound(smooth.begin(), smooth.end(), t,
                                                     [](const io::TrajectorySample& s, std::int64_t v) { return s.t_ns < v; }) -
                                    smooth.begin());
  };
  const std::size_t spike = at(5.0), step = at(12.0);
  const Vec3 spike_offset(0.13, -0.02, 0.05);
  const Vec3 step_offset = Vec3(1.0, -1.0, 0.5).normalized() * 0.02;
  io::Trajectory glitched = smooth;
  const auto shift = [](io::TrajectorySample& s, const Vec3& d) { s.T_w_b = SE3(s.T_w_b.so3(), s.T_w_b.translation() + d); };
  shift(glitched[spike], spike_offset);
  for (std::size_t i = step; i < glitched.size(); ++i) shift(glitched[i], step_offset);

  const double spread_s = 1.0;
  EXPECT_EQ(removePositionSteps(glitched, 50.0, spread_s), 3);
  const double dt = 1e-9 * static_cast<double>(smooth[1].t_ns - smooth[0].t_ns);
  const double eps = 1e-4;
  const std::size_t ramp_begin = at(12.0 - 0.5 * spread_s) - 1, ramp_end = at(12.0 + 0.5 * spread_s) + 1;
  Vec3 previous = Vec3::Zero();
  for (std::size_t i = 0; i < glitched.size(); ++i) {
    const Vec3 offset = glitched[i].T_w_b.translation() - smooth[i].T_w_b.translation();
    EXPECT_EQ(glitched[i].T_w_b.so3().matrix(), smooth[i].T_w_b.so3().matrix());
    if (i < ramp_begin) {
      ASSERT_LT(offset.norm(), eps) << "sample " << i << " (spike at " << spike << ")";
    } else if (i > ramp_end) {
      ASSERT_LT((offset - step_offset).norm(), eps) << "sample " << i;
    } else {
      // On the ramp: along the step, between 0 and s, growing by at most |s|·Δt/spread.
      const double along = offset.dot(step_offset.normalized());
      ASSERT_LT((offset - along * step_offset.normalized()).norm(), eps) << "sample " << i;
      ASSERT_GT(along, -eps);
      ASSERT_LT(along, step_offset.norm() + eps);
      ASSERT_LT((offset - previous).norm(), step_offset.norm() * dt / spread_s * 1.01 + eps) << "sample " << i;
    }
    previous = offset;
  }

  io::Trajectory untouched = smooth;
  shift(untouched[spike], spike_offset);
  EXPECT_EQ(removePositionSteps(untouched, 0.0, spread_s), 0);  // 0: off
  EXPECT_EQ(untouched[spike].T_w_b.translation(), smooth[spike].T_w_b.translation() + spike_offset);
}

}  // namespace
}  // namespace edgevio::sim
