// The window's maths: tracking-link Jacobians, and marginalisation: solving
// with the prior must give the same states as the full problem (issue #6).
#include "edgevio/estimator/sliding_window.h"
#include "edgevio/estimator/external_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "common/test_support.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/imu_synth.h"
#include "edgevio/sim/random.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::estimator {
namespace {

using geometry::SE3;
using geometry::SO3;
using imu::NavState;

TEST(Factors, RelativePoseJacobiansMatchNumeric) {
  sim::Rng rng(3);
  const auto v3 = [&](double s) -> Vec3 { return Vec3(rng.gaussian(), rng.gaussian(), rng.gaussian()) * s; };
  const SE3 T_b_c = io::eurocDefaultRig().T_b_c[0];
  for (int trial = 0; trial < 5; ++trial) {
    NavState r, n;
    r.R_w_b = SO3::exp(v3(1.0));
    r.p_w = v3(1.0);
    n.R_w_b = SO3::exp(v3(1.0));
    n.p_w = v3(1.0);
    const SE3 meas = SE3::exp((Vec6() << v3(0.5), v3(0.3)).finished());
    Mat6x15 Jr, Jn;
    relativePoseResidual(meas, r, n, T_b_c, &Jr, &Jn);
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(15);
    const auto fr = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd { return relativePoseResidual(meas, boxplus(r, d), n, T_b_c); };
    const auto fn = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd { return relativePoseResidual(meas, r, boxplus(n, d), T_b_c); };
    test::expectJacobianNear(Jr, test::numericJacobian(fr, zero, 1e-6), 1e-6, "dr/dx_r");
    test::expectJacobianNear(Jn, test::numericJacobian(fn, zero, 1e-6), 1e-6, "dr/dx_n");
    Mat6 Jc;
    relativePoseResidual(meas, r, n, T_b_c, nullptr, nullptr, &Jc);
    const auto fc = [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
      return relativePoseResidual(meas, r, n, T_b_c * SE3::exp(d));
    };
    test::expectJacobianNear(Jc, test::numericJacobian(fc, Eigen::VectorXd::Zero(6), 1e-6), 1e-6, "dr/dT_b_c");
  }
}

TEST(Factors, HuberScalesOnlyLargeBlocks) {
  const Mat6 I = Mat6::Identity();
  Vec6 small, big;
  small << 0.01, 0, 0, 0.001, 0, 0;
  big << 0.5, 0, 0, 0.001, 0, 0;
  EXPECT_EQ(huberWeightedInformation(I, small, 0.1, 0.035), I);
  const Mat6 W = huberWeightedInformation(I, big, 0.1, 0.035);
  EXPECT_NEAR(W(0, 0), 0.1 / 0.5, 1e-12);
  EXPECT_NEAR(W(4, 4), 1.0, 1e-12);
}

/// Seven states along the aggressive scenario at 10 Hz with noisy IMU and
/// noisy relative-pose links (consecutive, and from state 0 as a keyframe).
Window syntheticWindow(std::vector<NavState>* truth) {
  const camera::StereoRig rig = io::eurocDefaultRig();
  const io::Trajectory samples = sim::scenarioSamples("aggressive", 8.0, 1.0, rig.T_b_c[0]);
  const sim::SplineTrajectory s =
      sim::fitSpline(samples, sim::kScenarioStartNs, sim::kScenarioStartNs + 7000000000LL, 0.05, 0.1, "test");
  sim::ImuSynthOptions io;
  const sim::SynthesizedImu imu = sim::synthesizeImu(s, s.beginNs(), s.endNs(), io, 4);
  sim::Rng rng(8);
  const auto v3 = [&](double sd) -> Vec3 { return Vec3(rng.gaussian(), rng.gaussian(), rng.gaussian()) * sd; };
  Window w;
  w.T_b_c = rig.T_b_c[0];
  const std::size_t first = 600, step = 20;  // 0.1 s apart
  for (std::size_t k = 0; k < 7; ++k) {
    const std::size_t idx = first + k * step;
    const sim::KinematicState ks = s.evaluate(imu.samples[idx].t_ns);
    NavState x;
    x.R_w_b = ks.T_w_b.so3();
    x.p_w = ks.T_w_b.translation();
    x.v_w = ks.v_w;
    x.b_a = imu.b_a[idx];
    x.b_g = imu.b_g[idx];
    truth->push_back(x);
    // Start the estimate away from the truth.
    NavState init = x;
    init.p_w += v3(0.05);
    init.R_w_b = x.R_w_b * SO3::exp(v3(0.02));
    init.v_w += v3(0.05);
    w.states.push_back({imu.samples[idx].t_ns, init, 0.0, imu.samples[idx].gyro, {}});
    if (k > 0) {
      imu::Preintegration p(Vec3::Zero(), Vec3::Zero(), imu::ImuNoise{});
      for (std::size_t m = idx - step; m < idx; ++m)
        p.integrate(static_cast<double>(imu.samples[m + 1].t_ns - imu.samples[m].t_ns) * 1e-9, imu.samples[m].accel,
                    imu.samples[m].gyro, imu.samples[m + 1].accel, imu.samples[m + 1].gyro);
      w.inertial.push_back({k - 1, k, p});
    }
  }
  const auto camPose = [&](const NavState& x) { return SE3(x.R_w_b, x.p_w) * w.T_b_c; };
  const double st = 0.005, sr = 0.003;
  for (std::size_t k = 1; k < 7; ++k)
    for (std::size_t r : {std::size_t{0}, k - 1}) {
      if (r == 0 && k == 1) continue;
      RelativePoseLink l;
      Vec6 noise;
      noise << v3(st), v3(sr);
      l.T_nr = camPose((*truth)[k]).inverse() * camPose((*truth)[r]) * SE3::exp(noise);
      l.information.setZero();
      l.information.diagonal() << Vec3::Constant(1 / (st * st)), Vec3::Constant(1 / (sr * sr));
      w.visual.push_back({r, k, l, nullptr});
    }
  // Anchor state 0 with a strong prior (the gauge of this test problem).
  w.gauge = Gauge::kNone;
  w.prior.states = {0};
  w.prior.x0 = {(*truth)[0]};
  w.prior.H = Eigen::MatrixXd::Identity(15, 15) * 1e8;
  w.prior.b = Eigen::VectorXd::Zero(15);
  return w;
}

EstimatorOptions exactOptions() {
  EstimatorOptions o;
  o.max_iterations = 50;
  o.first_estimate_jacobians = false;
  o.huber_translation_m = o.huber_rotation_deg = 1e9;  // Huber off: a pure least-squares problem
  return o;
}

TEST(SlidingWindow, SolveReachesTheNoiseLevel) {
  std::vector<NavState> truth;
  Window w = syntheticWindow(&truth);
  const SolveSummary s = solve(&w, exactOptions());
  EXPECT_LT(s.final_cost, s.initial_cost);
  for (std::size_t k = 0; k < truth.size(); ++k) {
    EXPECT_LT((w.states[k].x.p_w - truth[k].p_w).norm(), 0.02) << k;
    EXPECT_LT(geometry::angle(w.states[k].x.R_w_b.inverse() * truth[k].R_w_b), 0.01) << k;
  }
}

/// The visual links' cost when the links from one reference state share a
/// part of their error, r_i = b + e_i with Cov(e_i) = (1 − c)Σ_i and
/// Cov(b) = c·mean(Σ_i): ½ rᵀC⁻¹r over each group's stacked residuals, C
/// built whole (the window's Woodbury form must give the same).
double jointVisualCost(const Window& w, double c) {
  std::map<std::size_t, std::vector<const VisualLink*>> groups;
  for (const VisualLink& l : w.visual) groups[l.r].push_back(&l);
  double cost = 0.0;
  for (const auto& [reference, links] : groups) {
    const long m = static_cast<long>(links.size());
    Eigen::VectorXd r(6 * m);
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(6 * m, 6 * m);
    Mat6 mean = Mat6::Zero();
    for (long i = 0; i < m; ++i) {
      const VisualLink& l = *links[static_cast<std::size_t>(i)];
      r.segment<6>(6 * i) = relativePoseResidual(l.link.T_nr, w.states[l.r].x, w.states[l.n].x, w.T_b_c);
      const Mat6 covariance = l.link.information.inverse();
      C.block<6, 6>(6 * i, 6 * i) += (1.0 - c) * covariance;
      mean += covariance / static_cast<double>(m);
    }
    for (long i = 0; i < m; ++i)
      for (long j = 0; j < m; ++j) C.block<6, 6>(6 * i, 6 * j) += c * mean;
    cost += 0.5 * r.dot(C.ldlt().solve(r));
  }
  return cost;
}

TEST(SlidingWindow, LinksFromOneKeyframeAreWeighedJointlyWithTheirSharedError) {
  // Six links from state 0 (one group) and five lone ones: the window's cost
  // moves by exactly the joint model's change of the visual part.
  std::vector<NavState> truth;
  const Window w = syntheticWindow(&truth);
  const EstimatorOptions independent = exactOptions();
  for (const double c : {0.3, 0.6, 0.9}) {
    EstimatorOptions shared = exactOptions();
    shared.visual_shared_fraction = c;
    const double expected = jointVisualCost(w, c) - jointVisualCost(w, 0.0);
    const double with = windowCost(w, shared), without = windowCost(w, independent);
    // Rounding: about 1e-13 of the costs summed (the stiff prior's terms
    // among them), and of the 6m x 6m factorisation's result.
    EXPECT_NEAR(with - without, expected, 1e-13 * (with + without) + 1e-12 * std::abs(expected)) << c << ": " << with;
  }
}

class SharedErrorSolve : public ::testing::TestWithParam<bool> {};

TEST_P(SharedErrorSolve, EndsWhereTheCostIsFlat) {
  // The gradient and normal matrix the solve builds must be the cost's: at
  // its end every central difference of the cost along each state's 15
  // directions (and the calibration's, when estimated) is zero, relative to
  // what it was at the start.
  std::vector<NavState> truth;
  Window w = syntheticWindow(&truth);
  if (GetParam()) {
    w.calibration = CalibrationState{};
    w.calibration->time_offset = w.calibration->rotation = w.calibration->translation = true;
  }
  EstimatorOptions o = exactOptions();
  o.visual_shared_fraction = 0.6;
  const double h = 1e-6;
  const auto central = [&](const Window& plus, const Window& minus) {
    return (windowCost(plus, o) - windowCost(minus, o)) / (2 * h);
  };
  const auto gradientNorm = [&](const Window& at) {
    double sum = 0.0;
    for (int d = 0; d < 15; ++d) {
      for (std::size_t k = 1; k < at.states.size(); ++k) {  // state 0: held by the test's stiff prior
        Window plus = at, minus = at;
        plus.states[k].x = boxplus(at.states[k].x, imu::Vec15::Unit(d) * h);
        minus.states[k].x = boxplus(at.states[k].x, imu::Vec15::Unit(d) * -h);
        sum += std::pow(central(plus, minus), 2);
      }
      if (at.calibration && d < 7) {
        Window plus = at, minus = at;
        plus.calibration = boxplus(*at.calibration, imu::Vec15::Unit(d) * h);
        minus.calibration = boxplus(*at.calibration, imu::Vec15::Unit(d) * -h);
        sum += std::pow(central(plus, minus), 2);
      }
    }
    return std::sqrt(sum);
  };
  const double before = gradientNorm(w);
  solve(&w, o);
  EXPECT_LT(gradientNorm(w), 1e-5 * before) << "at the start " << before;
}

INSTANTIATE_TEST_SUITE_P(SlidingWindow, SharedErrorSolve, ::testing::Values(false, true),
                         [](const ::testing::TestParamInfo<bool>& p) { return p.param ? "WithCalibration" : "States"; });

void expectMarginalizationEquivalent(std::size_t removed, bool first_estimate_jacobians = false, bool calibration = false) {
  std::vector<NavState> truth;
  Window full = syntheticWindow(&truth);
  if (calibration) {
    full.calibration = CalibrationState{};
    full.calibration->time_offset = full.calibration->rotation = full.calibration->translation = true;
  }
  EstimatorOptions o = exactOptions();
  o.first_estimate_jacobians = first_estimate_jacobians;
  solve(&full, o);  // converged full problem
  Window reduced = full;
  marginalize(&reduced, removed, o);
  ASSERT_EQ(reduced.states.size(), full.states.size() - 1);
  // Perturb the reduced problem's start so the solve has work to do.
  for (auto& s : reduced.states) s.x.p_w += Vec3(0.01, -0.01, 0.005);
  solve(&reduced, o);
  double worst = 0.0;
  for (std::size_t k = 0, r = 0; k < full.states.size(); ++k) {
    if (k == removed) continue;
    worst = std::max(worst, boxminus(reduced.states[r].x, full.states[k].x).norm());
    ++r;
  }
  if (calibration) worst = std::max(worst, boxminus(*reduced.calibration, *full.calibration).norm());
  std::printf("marginalising state %zu: max state difference %.2e\n", removed, worst);
  EXPECT_LT(worst, 1e-6);
}

TEST(SlidingWindow, MarginalisingAMiddleStateKeepsTheSolution) { expectMarginalizationEquivalent(3); }
TEST(SlidingWindow, MarginalisingKeepsTheSolutionWithTheCalibrationEstimated) {
  expectMarginalizationEquivalent(3, false, true);
  expectMarginalizationEquivalent(0, true, true);
}
TEST(SlidingWindow, MarginalisingTheOldestStateKeepsTheSolution) { expectMarginalizationEquivalent(0); }
TEST(SlidingWindow, WithFirstEstimateJacobiansMarginalisingKeepsTheSolution) {
  expectMarginalizationEquivalent(3, true);
  expectMarginalizationEquivalent(0, true);
}

/// Marginalising state k of the synthetic window with and without
/// front_marginalization_drops_links, and, with the option off, a copy of the
/// window whose links measured in k are removed beforehand.
struct DroppedLinks {
  Window dropping, keeping, without_them;
};

DroppedLinks marginalizeDroppingLinks(std::size_t k) {
  std::vector<NavState> truth;
  Window w = syntheticWindow(&truth);
  EstimatorOptions keep = exactOptions(), drop = exactOptions();
  drop.front_marginalization_drops_links = true;
  solve(&w, keep);
  DroppedLinks d{w, w, w};
  auto& v = d.without_them.visual;
  v.erase(std::remove_if(v.begin(), v.end(), [k](const VisualLink& l) { return l.n == k; }), v.end());
  marginalize(&d.dropping, k, drop);
  marginalize(&d.keeping, k, keep);
  marginalize(&d.without_them, k, keep);
  return d;
}

TEST(SlidingWindow, FrontMarginalisationDropsOnlyTheLinksMeasuredInTheFrame) {
  // State 3 is measured from 0 and 2 and is the reference of 3 -> 4: the
  // prior must be the one left without the first two links, bit for bit,
  // and must differ from the one that folds them in.
  const DroppedLinks front = marginalizeDroppingLinks(3);
  EXPECT_EQ(front.dropping.prior.states, front.without_them.prior.states);
  EXPECT_EQ(front.dropping.prior.H, front.without_them.prior.H);
  EXPECT_EQ(front.dropping.prior.b, front.without_them.prior.b);
  EXPECT_EQ(front.dropping.visual.size(), front.keeping.visual.size());
  ASSERT_EQ(front.dropping.prior.H.rows(), front.keeping.prior.H.rows());
  // The links 0 -> 3 and 2 -> 3 are 3 mm / 3 mrad: their information is
  // ~1e5, far above the rounding of the rest.
  EXPECT_GT((front.dropping.prior.H - front.keeping.prior.H).norm(), 1e3);
  // The oldest state is back-marginalised: everything is folded either way.
  const DroppedLinks back = marginalizeDroppingLinks(0);
  EXPECT_EQ(back.dropping.prior.H, back.keeping.prior.H);
  EXPECT_EQ(back.dropping.prior.b, back.keeping.prior.b);
}

/// The solved window is the minimum of the cost over every state, so also
/// over the newest alone with the others held there: from a perturbed start
/// solveNewest must return the newest state to it and move no other.
void expectNewestStateFoundAlone(bool newest_in_prior) {
  std::vector<NavState> truth;
  Window solved = syntheticWindow(&truth);
  const EstimatorOptions o = exactOptions();
  solve(&solved, o);
  if (newest_in_prior) {  // the second-newest marginalised: the prior holds the newest
    marginalize(&solved, solved.states.size() - 2, o);
    solve(&solved, o);
    ASSERT_NE(std::find(solved.prior.states.begin(), solved.prior.states.end(), solved.states.size() - 1),
              solved.prior.states.end());
  }
  Window w = solved;
  NavState& newest = w.states.back().x;
  newest.p_w += Vec3(0.05, -0.03, 0.02);
  newest.R_w_b = newest.R_w_b * SO3::exp(Vec3(0.02, -0.01, 0.03));
  newest.v_w += Vec3(-0.1, 0.05, 0.1);
  newest.b_a += Vec3(0.01, 0.0, -0.01);
  const SolveSummary s = solveNewest(&w, o);
  EXPECT_LT(s.final_cost, s.initial_cost);
  // Gauss-Newton converges to the stationary point up to the links' second-order terms: 1e-6 of a 0.1 start.
  EXPECT_LT(boxminus(w.states.back().x, solved.states.back().x).norm(), 1e-6);
  for (std::size_t k = 0; k + 1 < w.states.size(); ++k) {
    EXPECT_EQ(w.states[k].x.p_w, solved.states[k].x.p_w) << k;
    EXPECT_EQ(w.states[k].x.v_w, solved.states[k].x.v_w) << k;
    EXPECT_EQ(w.states[k].x.R_w_b.matrix(), solved.states[k].x.R_w_b.matrix()) << k;
  }
}

TEST(SlidingWindow, TheNewestStateSolvedAloneReturnsToTheWindowsSolution) { expectNewestStateFoundAlone(false); }
TEST(SlidingWindow, TheNewestStateSolvedAloneReturnsToTheSolutionWhenThePriorHoldsIt) { expectNewestStateFoundAlone(true); }

/// ‖H·n‖ / (‖H‖·‖n‖) for the prior's Hessian H and n the infinitesimal change
/// of its states' errors under a gauge motion (a world translation along
/// `shift`, plus a rotation by yaw_rate about the world z axis), taken at the
/// prior's linearisation points.
double gaugeLeak(const MarginalPrior& prior, const Vec3& shift, double yaw_rate) {
  Eigen::VectorXd n(prior.H.rows());
  for (std::size_t k = 0; k < prior.states.size(); ++k) {
    const NavState& x = prior.x0[k];
    imu::Vec15 d = imu::Vec15::Zero();
    d.segment<3>(imu::kP) = shift + yaw_rate * Vec3::UnitZ().cross(x.p_w);
    d.segment<3>(imu::kR) = yaw_rate * (x.R_w_b.inverse() * Vec3::UnitZ());
    d.segment<3>(imu::kV) = yaw_rate * Vec3::UnitZ().cross(x.v_w);
    n.segment<15>(15 * static_cast<long>(k)) = d;
  }
  return (prior.H * n).norm() / (prior.H.norm() * n.norm());
}

TEST(SlidingWindow, FirstEstimateJacobiansKeepTheGaugeOutOfThePrior) {
  // Position and yaw are unobservable (eq 17 and the relative-pose residual
  // do not change under a world translation or a rotation about gravity). A
  // prior made from Jacobians at one consistent set of points inherits that
  // null space exactly; re-linearising the prior's states elsewhere after
  // they entered it (the default without FEJ) puts information into it.
  double leak[2] = {0, 0};
  for (const bool fej : {false, true}) {
    std::vector<NavState> truth;
    Window w = syntheticWindow(&truth);
    w.prior = MarginalPrior{};  // no anchor: the gauge is free
    w.gauge = Gauge::kPositionYaw;
    EstimatorOptions o;
    o.gauge_prior = true;
    o.first_estimate_jacobians = fej;
    o.max_iterations = 3;
    for (int round = 0; round < 3; ++round) {
      solve(&w, o);
      marginalize(&w, 0, o);
    }
    for (const Vec3& shift : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, 0, 1), Vec3(0, 0, 0)})
      leak[fej] = std::max(leak[fej], gaugeLeak(w.prior, shift, shift.isZero() ? 1.0 : 0.0));
  }
  std::printf("gauge directions in the prior, relative: %.1e without FEJ, %.1e with\n", leak[0], leak[1]);
  EXPECT_LT(leak[1], 1e-9);
  EXPECT_GT(leak[0], 100 * leak[1]);
}

class GaugeHold : public ::testing::TestWithParam<bool> {};

TEST_P(GaugeHold, KeepsTheOldestPositionAndYaw) {
  std::vector<NavState> truth;
  Window w = syntheticWindow(&truth);
  w.prior = MarginalPrior{};  // no anchor: the gauge must hold it
  w.gauge = Gauge::kPositionYaw;
  const NavState before = w.states.front().x;
  EstimatorOptions o;
  o.gauge_prior = GetParam();
  // Re-anchoring is exact; the stiff prior leaves a step of about
  // gradient / stiffness, 1e-3 of the unconstrained one, in those directions.
  const double tolerance = o.gauge_prior ? 1e-6 : 1e-9;
  solve(&w, o);
  const NavState after = w.states.front().x;
  EXPECT_LT((after.p_w - before.p_w).norm(), tolerance);
  // Yaw kept: the heading of the body axis that is most horizontal.
  const Mat3 R0 = before.R_w_b.matrix();
  int axis = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(R0(2, k)) < std::abs(R0(2, axis))) axis = k;
  const auto heading = [&](const SO3& R) { const Vec3 d = R * Vec3::Unit(axis); return std::atan2(d.y(), d.x()); };
  if (o.gauge_prior) {
    // The prior holds the rotation about world z at every step (first
    // order): what is left of it after several steps is of second order in
    // the roll and pitch they made.
    const Vec3 w_world = (after.R_w_b * before.R_w_b.inverse()).log();
    EXPECT_LT(std::abs(w_world.z()), 0.5 * w_world.squaredNorm() + tolerance);
  } else {
    EXPECT_NEAR(heading(after.R_w_b), heading(before.R_w_b), tolerance);
  }
  // Roll and pitch did move (the test must not pass by freezing the state).
  EXPECT_GT(geometry::angle(before.R_w_b.inverse() * after.R_w_b), 1e-4);
}

INSTANTIATE_TEST_SUITE_P(SlidingWindow, GaugeHold, ::testing::Values(false, true),
                         [](const auto& param_info) { return param_info.param ? std::string("Prior") : std::string("Reanchoring"); });

}  // namespace
}  // namespace edgevio::estimator

namespace edgevio::estimator {
namespace {

TEST(ExternalCheck, AcceptsTrueLinksAndRejectsACorruptedOne) {
  std::vector<NavState> truth;
  const Window w = syntheticWindow(&truth);
  int accepted = 0;
  for (const InertialLink& l : w.inertial) {
    // The IMU prediction from the true state r (noisy IMU, 0.1 s).
    const NavState pred = imu::predictState(truth[l.i], l.pre);
    const SE3 C_r = SE3(truth[l.i].R_w_b, truth[l.i].p_w) * w.T_b_c, C_n = SE3(truth[l.j].R_w_b, truth[l.j].p_w) * w.T_b_c;
    const SE3 true_link = C_n.inverse() * C_r;
    const ExternalCheckResult good = externalCheck(true_link, truth[l.i], pred, w.T_b_c, 3.0, 0.2);
    accepted += good.accepted;
    // A wrong minimum of the alignment: 10 deg and 30 cm off.
    const SE3 corrupted = true_link * SE3(SO3::exp(Vec3(0, 0.1745, 0)), Vec3(0.3, 0, 0));
    const ExternalCheckResult bad = externalCheck(corrupted, truth[l.i], pred, w.T_b_c, 3.0, 0.2);
    EXPECT_FALSE(bad.accepted);
    EXPECT_NEAR(bad.rotation_deg, 10.0, 0.5);
  }
  EXPECT_EQ(accepted, static_cast<int>(w.inertial.size()));
}

}  // namespace
}  // namespace edgevio::estimator
