// Trajectory metrics on synthetic trajectories whose error is known in closed
// form, and on the evo reference pair in shared/data.
#include "edgevio/eval/metrics.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/test_support.h"
#include "edgevio/common/error.h"

namespace edgevio::eval {
namespace {

using geometry::SE3;
using geometry::SO3;
constexpr double kDeg = kRadToDeg;

/// A smooth 3-D loop sampled at 20 Hz for `seconds`.
io::Trajectory loop(double seconds) {
  io::Trajectory t;
  for (int i = 0; i <= static_cast<int>(seconds * 20); ++i) {
    const double s = i / 20.0;
    io::TrajectorySample p;
    p.t_ns = 1000000000LL + static_cast<std::int64_t>(i) * 50000000LL;
    p.T_w_b = SE3(SO3::exp(Vec3(0.1 * std::sin(s), 0.2 * std::cos(0.5 * s), 0.3 * s)),
                  Vec3(3.0 * std::cos(0.3 * s), 2.0 * std::sin(0.3 * s), 1.0 + 0.3 * std::sin(0.7 * s)));
    t.push_back(p);
  }
  return t;
}

io::Trajectory transformed(const io::Trajectory& in, const Similarity& S) {
  io::Trajectory out = in;
  for (auto& p : out) p.T_w_b = S.apply(p.T_w_b);
  return out;
}

EvalOptions withAlignment(AlignmentKind a) {
  EvalOptions o;
  o.alignment = a;
  return o;
}

TEST(Metrics, IdenticalTrajectoriesHaveZeroError) {
  const io::Trajectory gt = loop(30);
  const EvalResult r = evaluate(gt, gt, EvalOptions{});
  EXPECT_EQ(r.matched, gt.size());
  EXPECT_LT(r.ate_rmse_m, 1e-9);
  EXPECT_LT(r.are_rot_deg_per_m, 1e-6);
  EXPECT_LT(r.are_trans_m_per_m, 1e-9);
  for (const auto& e : r.rpe) EXPECT_LT(e.trans_rmse_m, 1e-9);
}

TEST(Metrics, ConstantOffsetIsRemovedByAlignmentAndMeasuredWithout) {
  const io::Trajectory gt = loop(30);
  Similarity offset;
  offset.T = SE3(SO3(), Vec3(0.3, -0.4, 1.2));  // |offset| = 1.3 m
  const io::Trajectory est = transformed(gt, offset);
  const EvalResult none = evaluate(gt, est, withAlignment(AlignmentKind::kNone));
  EXPECT_NEAR(none.ate_rmse_m, 1.3, 1e-9);
  EXPECT_NEAR(none.ate_max_m, 1.3, 1e-9);
  EXPECT_NEAR(none.ate_median_m, 1.3, 1e-9);
  EXPECT_LT(evaluate(gt, est, withAlignment(AlignmentKind::kSe3)).ate_rmse_m, 1e-9);
  EXPECT_LT(evaluate(gt, est, withAlignment(AlignmentKind::kPosYaw)).ate_rmse_m, 1e-9);
  // Relative metrics ignore a global offset.
  EXPECT_LT(none.are_trans_m_per_m, 1e-9);
}

TEST(Metrics, KnownScaleIsRecoveredBySim3Only) {
  const io::Trajectory gt = loop(30);
  Similarity S;
  S.scale = 1.25;
  S.T = SE3(SO3::exp(Vec3(0.2, -0.1, 0.7)), Vec3(1, 2, 3));
  const io::Trajectory est = transformed(gt, S);
  const EvalResult sim3 = evaluate(gt, est, withAlignment(AlignmentKind::kSim3));
  EXPECT_LT(sim3.ate_rmse_m, 1e-9);
  EXPECT_NEAR(sim3.transform.scale, 1.0 / 1.25, 1e-12);
  EXPECT_GT(evaluate(gt, est, withAlignment(AlignmentKind::kSe3)).ate_rmse_m, 0.1);
}

TEST(Metrics, YawRotationIsRemovedByPosYawButNotRollPitch) {
  const io::Trajectory gt = loop(30);
  Similarity yaw;
  yaw.T = SE3(SO3::exp(Vec3(0, 0, 0.8)), Vec3(0.5, 0.1, -0.2));
  EXPECT_LT(evaluate(gt, transformed(gt, yaw), withAlignment(AlignmentKind::kPosYaw)).ate_rmse_m, 1e-9);
  EXPECT_LT(evaluate(gt, transformed(gt, yaw), withAlignment(AlignmentKind::kSe3)).ate_rmse_m, 1e-9);
  EXPECT_GT(evaluate(gt, transformed(gt, yaw), withAlignment(AlignmentKind::kNone)).ate_rmse_m, 0.5);
  Similarity roll;
  roll.T = SE3(SO3::exp(Vec3(0.3, 0, 0)), Vec3::Zero());
  EXPECT_GT(evaluate(gt, transformed(gt, roll), withAlignment(AlignmentKind::kPosYaw)).ate_rmse_m, 0.05);
  EXPECT_LT(evaluate(gt, transformed(gt, roll), withAlignment(AlignmentKind::kSe3)).ate_rmse_m, 1e-9);
}

TEST(Metrics, NoiseOfKnownRms) {
  // Every position is displaced by exactly σ in a direction that turns with i:
  // without alignment RMSE = mean = median = max = σ.
  const io::Trajectory gt = loop(30);
  io::Trajectory est = gt;
  const double sigma = 0.05;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const double a = 2.399963 * static_cast<double>(i);  // golden angle: directions spread evenly
    est[i].T_w_b = SE3(est[i].T_w_b.so3(), est[i].T_w_b.translation() + sigma * Vec3(std::cos(a), std::sin(a), 0.0));
  }
  const EvalResult r = evaluate(gt, est, withAlignment(AlignmentKind::kNone));
  EXPECT_NEAR(r.ate_rmse_m, sigma, 1e-12);
  EXPECT_NEAR(r.ate_mean_m, sigma, 1e-12);
  EXPECT_NEAR(r.ate_max_m, sigma, 1e-12);
  // Alignment can only reduce the error of zero-mean noise.
  EXPECT_LE(evaluate(gt, est, withAlignment(AlignmentKind::kSe3)).ate_rmse_m, sigma + 1e-12);
}

/// Straight line along x, one pose per metre, identity orientation.
std::vector<SE3> line(int n, double spacing) {
  std::vector<SE3> poses;
  for (int i = 0; i < n; ++i) poses.emplace_back(SO3(), Vec3(spacing * i, 0, 0));
  return poses;
}

TEST(Metrics, AreByHandForScaleDrift) {
  // gt: x = 0..10 m; est: x scaled by 1.1. With L = 5 m the segments start at
  // i = 0..5 and end at i + 5; each has E = translation (0.5, 0, 0):
  // ARE-trans = 0.5 / 5 = 0.1 m/m, ARE-rot = 0.
  const std::vector<SE3> gt = line(11, 1.0), est = line(11, 1.1);
  const AreResult r = averageRelativeError(gt, est, {5.0});
  EXPECT_EQ(r.segments, 6u);
  EXPECT_NEAR(r.trans_m_per_m, 0.1, 1e-12);
  EXPECT_NEAR(r.rot_deg_per_m, 0.0, 1e-12);
}

TEST(Metrics, AreByHandForYawDrift) {
  // est pose k has yaw k·α at the gt position. For the segment (i, i+5):
  // E = (Rz(5α), Rz(−iα)(5,0,0) − (5,0,0)), so angle(E)/L = 5α/5 = α [rad/m] and
  // ‖trans(E)‖/L = 2 sin(iα/2). Averages over i = 0..5.
  const double alpha = 0.02;
  const std::vector<SE3> gt = line(11, 1.0);
  std::vector<SE3> est = gt;
  for (int k = 0; k < 11; ++k) est[static_cast<std::size_t>(k)] = SE3(SO3::exp(Vec3(0, 0, k * alpha)), gt[static_cast<std::size_t>(k)].translation());
  double expected_trans = 0.0;
  for (int i = 0; i <= 5; ++i) expected_trans += 2.0 * std::sin(i * alpha / 2.0);
  expected_trans /= 6.0;
  const AreResult r = averageRelativeError(gt, est, {5.0});
  EXPECT_EQ(r.segments, 6u);
  EXPECT_NEAR(r.rot_deg_per_m, alpha * kDeg, 1e-9);
  EXPECT_NEAR(r.trans_m_per_m, expected_trans, 1e-12);
}

TEST(Metrics, RpePairsFollowEvoPathConvention) {
  // Poses 0.4 m apart: the path reaches 1 m at index 3 (1.2 m), then 1 m again
  // from there at 6, then 9: pairs (3,6), (6,9).
  const auto pairs = rpePairsByPath(line(11, 0.4), 1.0);
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_EQ(pairs[0], std::make_pair(std::size_t{3}, std::size_t{6}));
  EXPECT_EQ(pairs[1], std::make_pair(std::size_t{6}, std::size_t{9}));
  // RPE of a 10 % scale error over pairs 1.2 m apart: 0.12 m each.
  const RpeResult r = relativePoseError(line(11, 0.4), line(11, 0.44), 1.0);
  // Pairs come from the estimate: spacing 0.44 reaches 1 m at index 3 as well.
  EXPECT_EQ(r.pairs, 2u);
  EXPECT_NEAR(r.trans_rmse_m, 0.12, 1e-12);
}

TEST(Metrics, TooShortForRpeGivesNoPairsNotACrash) {
  const RpeResult r = relativePoseError(line(3, 0.1), line(3, 0.1), 5.0);
  EXPECT_EQ(r.pairs, 0u);
  EXPECT_TRUE(std::isnan(r.trans_rmse_m));
}

TEST(Metrics, AssociationToleranceAndNearestMatch) {
  io::Trajectory gt = loop(2);  // 41 poses, 50 ms apart
  io::Trajectory est;
  for (std::size_t i = 0; i < gt.size(); i += 4) {
    io::TrajectorySample s = gt[i];
    s.t_ns += 9000000;  // 9 ms late: still within the 10 ms tolerance
    est.push_back(s);
  }
  Association a = associate(gt, est, 10000000);
  EXPECT_EQ(a.size(), est.size());
  EXPECT_EQ(a.t_ns[1], gt[4].t_ns);
  for (auto& s : est) s.t_ns += 2000000;  // 11 ms: beyond
  EXPECT_EQ(associate(gt, est, 10000000).size(), 0u);
}

TEST(Metrics, BadInputIsExplained) {
  const io::Trajectory gt = loop(5);
  io::Trajectory late = gt;
  for (auto& s : late) s.t_ns += 100000000000LL;
  test::expectInputError([&] { evaluate(gt, late, EvalOptions{}); }, {"no timestamp overlap"});
  const io::Trajectory two(gt.begin(), gt.begin() + 2);
  test::expectInputError([&] { evaluate(gt, two, EvalOptions{}); }, {"needs at least 3"});
  EXPECT_NO_THROW(evaluate(gt, two, withAlignment(AlignmentKind::kPosYaw)));
}

TEST(Metrics, ReproducesTheEvoReferenceFigures) {
  EDGEVIO_REQUIRE_SHARED_DATA("eval_reference");
  const io::Trajectory gt = io::readTrajectory(data_path + "/V1_02_groundtruth.csv");
  const io::Trajectory est = io::readTrajectory(data_path + "/V1_02_estimate_tum.txt");
  // Figures computed by evo, printed to 6 decimals (shared/data/README.md).
  const double tol = 1e-6;
  EvalOptions o;
  const EvalResult se3 = evaluate(gt, est, o);
  EXPECT_EQ(se3.matched, 798u);
  EXPECT_NEAR(se3.ate_rmse_m, 0.091727, tol);
  ASSERT_EQ(se3.rpe.size(), 2u);
  EXPECT_NEAR(se3.rpe[0].trans_rmse_m, 0.053234, tol);
  EXPECT_NEAR(se3.rpe[0].rot_rmse_deg, 1.076308, tol);
  EXPECT_NEAR(se3.rpe[1].trans_rmse_m, 0.093719, tol);
  EXPECT_NEAR(se3.rpe[1].rot_rmse_deg, 1.127444, tol);
  o.alignment = AlignmentKind::kSim3;
  EXPECT_NEAR(evaluate(gt, est, o).ate_rmse_m, 0.083841, tol);
}

}  // namespace
}  // namespace edgevio::eval
