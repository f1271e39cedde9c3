// IMU preintegration (METHOD.md §4): against simulator ground truth with
// noise off, residual Jacobians against numeric differentiation, the
// first-order bias correction against re-integration, and the propagated
// covariance against a Monte Carlo spread.
#include "edgevio/imu/preintegration.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "common/test_support.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/imu_synth.h"
#include "edgevio/sim/random.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::imu {
namespace {

using geometry::SO3;

struct Motion {
  sim::SplineTrajectory spline;
  sim::SynthesizedImu imu;
};

Motion motion(const std::string& scenario, bool noise, std::uint64_t seed = 1) {
  const camera::StereoRig rig = io::eurocDefaultRig();
  const io::Trajectory s = sim::scenarioSamples(scenario, 12.0, 1.0, rig.T_b_c[0]);
  Motion m{sim::fitSpline(s, sim::kScenarioStartNs, sim::kScenarioStartNs + 11000000000LL, 0.05, 0.1, scenario), {}};
  sim::ImuSynthOptions o;
  o.noise = noise;
  m.imu = sim::synthesizeImu(m.spline, m.spline.beginNs(), m.spline.endNs(), o, seed);
  return m;
}

Preintegration preintegrateSpan(const sim::SynthesizedImu& imu, std::size_t k0, std::size_t k1, const Vec3& ba, const Vec3& bg) {
  const auto p = preintegrate(imu.samples, imu.samples[k0].t_ns, imu.samples[k1].t_ns, ba, bg, imu::ImuNoise{});
  EXPECT_TRUE(p.has_value());
  return p.value_or(Preintegration(ba, bg, imu::ImuNoise{}));
}

NavState trueState(const Motion& m, std::size_t k) {
  const sim::KinematicState s = m.spline.evaluate(m.imu.samples[k].t_ns);
  NavState n;
  n.R_w_b = s.T_w_b.so3();
  n.p_w = s.T_w_b.translation();
  n.v_w = s.v_w;
  n.b_a = m.imu.b_a[k];
  n.b_g = m.imu.b_g[k];
  return n;
}

TEST(Preintegration, ResidualVanishesAtGroundTruthWithNoiseOff) {
  for (const std::string name : {"figure8", "aggressive", "throw"}) {
    const Motion m = motion(name, false);
    for (std::size_t span : {std::size_t{10}, std::size_t{200}}) {  // one frame (50 ms) and 1 s
      double worst_p = 0, worst_r = 0, worst_v = 0;
      for (std::size_t k0 = 0; k0 + span < m.imu.samples.size(); k0 += 97) {
        const Preintegration p = preintegrateSpan(m.imu, k0, k0 + span, Vec3::Zero(), Vec3::Zero());
        const Vec15 r = p.residual(trueState(m, k0), trueState(m, k0 + span));
        worst_p = std::max(worst_p, r.segment<3>(kP).norm());
        worst_r = std::max(worst_r, r.segment<3>(kR).norm() * kRadToDeg);
        worst_v = std::max(worst_v, r.segment<3>(kV).norm());
      }
      std::printf("%s, %zu samples: worst |r_p| %.2e m, |r_theta| %.2e deg, |r_v| %.2e m/s\n", name.c_str(), span,
                  worst_p, worst_r, worst_v);
      // Same bounds as the simulator's IMU consistency (issue #4): 1 cm and 0.1 deg over 1 s.
      EXPECT_LT(worst_p, 0.01) << name;
      EXPECT_LT(worst_r, 0.1) << name;
      EXPECT_LT(worst_v, 0.02) << name;
    }
  }
}

NavState randomState(sim::Rng& rng) {
  const auto v3 = [&](double s) -> Vec3 { return Vec3(rng.gaussian(), rng.gaussian(), rng.gaussian()) * s; };
  NavState n;
  n.R_w_b = SO3::exp(v3(1.0));
  n.p_w = v3(2.0);
  n.v_w = v3(1.0);
  n.b_a = v3(0.05);
  n.b_g = v3(0.01);
  return n;
}

Vec15 perturbationOf(const Eigen::VectorXd& d) { return Vec15(d); }

NavState perturb(const NavState& s, const Vec15& d) {
  NavState o = s;
  o.p_w += d.segment<3>(kP);
  o.R_w_b = s.R_w_b * SO3::exp(d.segment<3>(kR));
  o.v_w += d.segment<3>(kV);
  o.b_a += d.segment<3>(kBa);
  o.b_g += d.segment<3>(kBg);
  return o;
}

TEST(Preintegration, ResidualJacobiansMatchNumeric) {
  const Motion m = motion("aggressive", true, 3);
  sim::Rng rng(17);
  for (int trial = 0; trial < 5; ++trial) {
    const Preintegration p = preintegrateSpan(m.imu, 300 + 150 * static_cast<std::size_t>(trial), 340 + 150 * static_cast<std::size_t>(trial),
                                          Vec3(0.02, -0.01, 0.03), Vec3(0.001, 0.002, -0.001));
    const NavState si = randomState(rng), sj = randomState(rng);
    Mat15 Ji, Jj;
    p.residual(si, sj, &Ji, &Jj);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(15);
    const auto fi = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd { return p.residual(perturb(si, perturbationOf(d)), sj); };
    const auto fj = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd { return p.residual(si, perturb(sj, perturbationOf(d))); };
    test::expectJacobianNear(Ji, test::numericJacobian(fi, zero, 1e-6), 1e-5, "dr/dx_i");
    test::expectJacobianNear(Jj, test::numericJacobian(fj, zero, 1e-6), 1e-5, "dr/dx_j");
  }
}

TEST(Preintegration, FirstOrderBiasCorrectionMatchesReintegration) {
  const Motion m = motion("aggressive", false);
  const Vec3 dba(0.03, -0.02, 0.04), dbg(0.002, -0.003, 0.001);
  Preintegration p = preintegrateSpan(m.imu, 500, 700, Vec3::Zero(), Vec3::Zero());  // 1 s
  NavState i, j;  // residual at identical states: r = −(corrected deltas) for the position/velocity parts
  i.b_a = dba;
  i.b_g = dbg;
  j.b_a = dba;
  j.b_g = dbg;
  const Vec15 corrected = p.residual(i, j);
  Preintegration q = p;
  q.repropagate(dba, dbg);
  const Vec15 exact = q.residual(i, j);
  NavState i0, j0;
  const Vec15 uncorrected = p.residual(i0, j0);
  for (int b : {kP, kR, kV}) {
    const double change = (exact.segment<3>(b) - uncorrected.segment<3>(b)).norm();
    const double left = (exact.segment<3>(b) - corrected.segment<3>(b)).norm();
    EXPECT_LT(left, 0.02 * change) << "block " << b << ": correction leaves " << left << " of " << change;
  }
}

TEST(Preintegration, CovarianceMatchesMonteCarlo) {
  // 0.5 s of noisy readings around a noise-free motion; the spread of the
  // deltas over 300 draws must match P's diagonal for α, θ, β (to the 3σ
  // sampling error of a variance from 300 draws, ~25 %).
  const Motion clean = motion("figure8", false);
  const Preintegration ref = preintegrateSpan(clean.imu, 600, 700, Vec3::Zero(), Vec3::Zero());
  const imu::ImuNoise n;
  sim::Rng rng(99);
  const double dt = 0.005;
  const double sa = n.accel_noise_density / std::sqrt(dt), sg = n.gyro_noise_density / std::sqrt(dt);
  Eigen::Matrix<double, 9, 1> sum_sq = Eigen::Matrix<double, 9, 1>::Zero();
  const int draws = 300;
  for (int d = 0; d < draws; ++d) {
    sim::SynthesizedImu noisy = clean.imu;
    for (std::size_t k = 600; k <= 700; ++k) {
      noisy.samples[k].accel += sa * Vec3(rng.gaussian(), rng.gaussian(), rng.gaussian());
      noisy.samples[k].gyro += sg * Vec3(rng.gaussian(), rng.gaussian(), rng.gaussian());
    }
    const Preintegration p = preintegrateSpan(noisy, 600, 700, Vec3::Zero(), Vec3::Zero());
    Eigen::Matrix<double, 9, 1> e;
    e.segment<3>(0) = p.alpha() - ref.alpha();
    e.segment<3>(3) = (ref.gamma().inverse() * p.gamma()).log();
    e.segment<3>(6) = p.beta() - ref.beta();
    sum_sq += e.cwiseProduct(e);
  }
  for (int b = 0; b < 3; ++b) {
    const double mc = sum_sq.segment<3>(3 * b).sum() / draws;
    const double predicted = ref.covariance().block<3, 3>(3 * b, 3 * b).trace();
    std::printf("block %d: Monte Carlo %.3e, propagated %.3e\n", b, mc, predicted);
    // The readings at both ends of each interval are shared by neighbouring
    // steps (midpoint rule), which the per-step noise model treats as
    // independent; that and sampling error stay within a factor 1.5.
    EXPECT_GT(mc / predicted, 1.0 / 1.5);
    EXPECT_LT(mc / predicted, 1.5);
  }
}

}  // namespace
}  // namespace edgevio::imu
