#pragma once
// A built-in scenario's motion as a spline with its IMU synthesised (noise and
// bias random walks at EuRoC's densities): the truth the estimator tests
// compare with, without images.
#include <string>

#include "edgevio/camera/calibration.h"
#include "edgevio/imu/preintegration.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/imu_synth.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::test {

struct ImuScenario {
  camera::StereoRig rig = io::eurocDefaultRig();
  sim::SplineTrajectory spline;
  sim::SynthesizedImu imu;
  /// 13 s of the named scenario (1 s standstill first), IMU from `seed`.
  explicit ImuScenario(const std::string& name, std::uint64_t seed = 21) {
    const io::Trajectory s = sim::scenarioSamples(name, 14.0, 1.0, rig.T_b_c[0]);
    spline = sim::fitSpline(s, sim::kScenarioStartNs, sim::kScenarioStartNs + 13000000000LL, 0.05, 0.1, name);
    sim::ImuSynthOptions o;  // noise and bias random walk on (EuRoC densities)
    imu = sim::synthesizeImu(spline, spline.beginNs(), spline.endNs(), o, seed);
  }
  imu::NavState truth(std::int64_t t) const {
    const sim::KinematicState k = spline.evaluate(t);
    imu::NavState x;
    x.R_w_b = k.T_w_b.so3();
    x.p_w = k.T_w_b.translation();
    x.v_w = k.v_w;
    return x;
  }
  geometry::SE3 pose(std::int64_t t) const { return spline.evaluate(t).T_w_b; }
  geometry::SE3 camera(const imu::NavState& x) const { return geometry::SE3(x.R_w_b, x.p_w) * rig.T_b_c[0]; }
};

}  // namespace edgevio::test
