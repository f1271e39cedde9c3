// Tight coupling's edge residuals (keyframe_structure.h): their derivatives
// against numeric differences of the cost, the points' inverse depths pulled
// back from a wrong depth when the links' poses are the truth, a window whose
// tight link pulls a frame back to its true pose, and marginalisation.
#include "edgevio/estimator/keyframe_structure.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include "common/render_fixture.h"
#include "edgevio/estimator/sliding_window.h"
#include "edgevio/tracking/alignment_options.h"
#include "edgevio/vision/keyframe_depth.h"

namespace edgevio::estimator {
namespace {

using geometry::SE3;
using geometry::SO3;

const test::RenderFixture& fixture() {
  static const test::RenderFixture f("figure8", 14.0);
  return f;
}

vision::EdgePyramid pyramidAt(std::size_t i) {
  const auto& fx = fixture();
  return vision::buildEdgePyramid(fx.frame(fx.path()[i].T_w_b, 0, i + 1).left, fx.rectifier().rectifiedCamera(),
                                  vision::VisionOptions{});
}

/// The keyframe at path sample i and at most `max_points` of its points.
struct Scene {
  std::shared_ptr<const tracking::KeyframeData> keyframe;
  KeyframePoints points;
};
Scene sceneAt(std::size_t i, int max_points, double disparity_sigma_px = 0.1) {
  const auto& fx = fixture();
  Scene s;
  s.keyframe = fx.keyframe(fx.path()[i].T_w_b, 0, i + 1);
  s.points = selectKeyframePoints(s.keyframe->depth, s.keyframe->pyramid.levels[0].camera, max_points, disparity_sigma_px,
                                  tracking::AlignmentOptions{}.max_normal_angle_deg);
  return s;
}

SE3 trueRelative(std::size_t i, std::size_t j) {
  const auto& fx = fixture();
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  return (fx.path()[j].T_w_b * T_b_c).inverse() * (fx.path()[i].T_w_b * T_b_c);
}

TEST(KeyframeStructure, DerivativesMatchTheCostsNumericDifferences) {
  // With one link and a stiff depth prior (I_ρ = 1e12: h_ρρ dwarfs the edge
  // terms, so the Schur complement leaves g_ξ as it is), g is ∂cost/∂ξ; each
  // point's g_ρ is ∂cost/∂ρ. Both against central differences of the cost,
  // summed over points so that a wrong sign or factor shows while the kinks
  // of a few points (a nearest line changing within ±ε) do not.
  Scene s = sceneAt(700, 200);
  ASSERT_GT(s.points.rays.size(), 150u);
  const vision::EdgePyramid cur = pyramidAt(705);
  const SE3 T = trueRelative(700, 705) * SE3::exp((Vec6() << 0.004, -0.003, 0.002, 0.002, -0.001, 0.0015).finished());
  const EdgeWeighting w{1.0, 3.0};
  s.points.rho_information = 1e12;
  const StructureSystem sys = linearizeStructure(s.points, {{T, &cur}}, w);
  ASSERT_GT(sys.residuals, 150);
  const double eps = 1e-6;
  for (int k = 0; k < 6; ++k) {
    Vec6 d = Vec6::Zero();
    d(k) = eps;
    const double up = linearizeStructure(s.points, {{T * SE3::exp(d), &cur}}, w, true).cost;
    const double down = linearizeStructure(s.points, {{T * SE3::exp(-d), &cur}}, w, true).cost;
    const double numeric = (up - down) / (2 * eps);
    EXPECT_NEAR(sys.g(k), numeric, 0.02 * std::abs(numeric) + 1e-3 * sys.g.norm()) << "twist component " << k;
  }
  // ∂/∂ρ with the prior at the usual strength, point by point through the cost's total.
  s.points.rho_information = 1.0;
  const StructureSystem soft = linearizeStructure(s.points, {{T, &cur}}, w);
  double analytic = 0.0, numeric = 0.0;
  for (std::size_t i = 0; i < s.points.rays.size(); ++i) {
    KeyframePoints up = s.points, down = s.points;
    const double h = 1e-7;
    up.rho[i] += h;
    down.rho[i] -= h;
    const double n = (linearizeStructure(up, {{T, &cur}}, w, true).cost - linearizeStructure(down, {{T, &cur}}, w, true).cost) / (2 * h);
    analytic += std::abs(soft.points[i].g_rho);
    numeric += std::abs(n);
    EXPECT_NEAR(soft.points[i].g_rho, n, 0.05 * std::abs(n) + 0.05) << "point " << i;
  }
  EXPECT_GT(numeric, 1.0);  // the test sees derivatives, not zeros
  EXPECT_NEAR(analytic, numeric, 0.02 * numeric);
}

TEST(KeyframeStructure, WithTheTruePosesTheEdgesCorrectAWrongDepth) {
  // Gauss-Newton in the inverse depths alone, the links' twists held at the
  // truth (dξ = 0), over five frames 0.1-0.5 s from the keyframe. Stereo's
  // inverse depths are scaled by 1.05 first (as a baseline 5 % long would),
  // prior and start alike, and the prior is loose (σ_d = 2 px): the frames'
  // parallax should pull the points most of the way back. (Stereo's own
  // error here, about 0.5 %, is below what the edges alone locate: 1.6 %
  // with no prior at all, measured; so only a larger error shows the pull.)
  const std::size_t i = 1200, gap = 20;
  Scene s = sceneAt(i, 300, 2.0);
  for (std::size_t k = 0; k < s.points.rays.size(); ++k) s.points.rho[k] = s.points.rho_stereo[k] *= 1.05;
  const cv::Mat depth = fixture().rectifiedDepth(fixture().path()[i].T_w_b);
  const camera::CameraModel& cam = fixture().rectifier().rectifiedCamera();
  std::vector<vision::EdgePyramid> frames;
  std::vector<StructureLink> links;
  for (std::size_t j = i + gap; j <= i + 5 * gap; j += gap) frames.push_back(pyramidAt(j));
  for (std::size_t a = 0; a < frames.size(); ++a) links.push_back({trueRelative(i, i + gap * (a + 1)), &frames[a]});
  // The median relative inverse-depth error of the points off silhouettes
  // (the true depth varies by less than 2 % over the pixel's 3x3 neighbours).
  const auto medianError = [&](const KeyframePoints& kp) {
    std::vector<double> e;
    for (std::size_t k = 0; k < kp.rays.size(); ++k) {
      const Vec2 uv = cam.project(kp.rays[k]);
      const int x = static_cast<int>(std::lround(uv.x())), y = static_cast<int>(std::lround(uv.y()));
      if (x < 1 || y < 1 || x >= depth.cols - 1 || y >= depth.rows - 1) continue;
      double lo = 1e9, hi = 0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          lo = std::min<double>(lo, depth.at<float>(y + dy, x + dx));
          hi = std::max<double>(hi, depth.at<float>(y + dy, x + dx));
        }
      if (hi > 1.02 * lo) continue;
      e.push_back(std::abs(kp.rho[k] * depth.at<float>(y, x) - 1.0));
    }
    EXPECT_GT(e.size(), 100u);
    std::nth_element(e.begin(), e.begin() + static_cast<long>(e.size() / 2), e.end());
    return e[e.size() / 2];
  };
  const double before = medianError(s.points);
  for (int it = 0; it < 5; ++it) {
    const StructureSystem sys = linearizeStructure(s.points, links, EdgeWeighting{1.0, 1.0});
    updateInverseDepths(sys, Eigen::VectorXd::Zero(6 * static_cast<long>(links.size())), &s.points);
  }
  const double after = medianError(s.points);
  std::printf("  median |ρ/ρ_true − 1| over %zu points: %.2f %% at the start, %.2f %% after five frames' edges\n",
              s.points.rays.size(), 100 * before, 100 * after);
  EXPECT_NEAR(before, 0.05, 0.01);
  EXPECT_LT(after, 0.5 * before);
}

TEST(KeyframeStructure, ATightLinkPullsAFrameBackToItsPose) {
  // Two states, no IMU: the keyframe held by the gauge, the frame 0.1 s later
  // started 3 cm and 1° away. Its tight link alone should bring its camera
  // to within the front end's accuracy of the truth (a few millimetres at
  // 1-4 m; the same as the alignment's, edge_alignment_e2e_test.cpp).
  const std::size_t i = 900, j = 920;
  const auto& fx = fixture();
  Window w;
  w.T_b_c = fx.rectifier().T_b_rect(0);
  w.gauge = Gauge::kPose;
  const auto state = [&](const SE3& T) {
    imu::NavState x;
    x.R_w_b = T.so3();
    x.p_w = T.translation();
    return x;
  };
  const SE3 T_w_bj = fx.path()[j].T_w_b;
  const SE3 start = T_w_bj * SE3::exp((Vec6() << 0.02, -0.02, 0.01, 0.01, -0.012, 0.008).finished());
  w.states.push_back({1, state(fx.path()[i].T_w_b), 0.0, Vec3::Zero(), sceneAt(i, 300).points});
  w.states.push_back({2, state(start), 0.0, Vec3::Zero(), {}});
  RelativePoseLink unused;
  w.visual.push_back({0, 1, unused, std::make_shared<const vision::EdgePyramid>(pyramidAt(j))});
  EstimatorOptions o;
  o.max_iterations = 10;
  const SolveSummary s = solve(&w, o);
  const SE3 T_est = SE3(w.states[1].x.R_w_b, w.states[1].x.p_w);
  const Vec6 e = (T_w_bj.inverse() * T_est).log();
  std::printf("  after %d iterations: %.2f mm, %.3f deg from the truth (cost %.1f -> %.1f)\n", s.iterations,
              1e3 * e.head<3>().norm(), e.tail<3>().norm() / kDegToRad, s.initial_cost, s.final_cost);
  EXPECT_LT(s.final_cost, s.initial_cost);
  EXPECT_LT(e.head<3>().norm(), 0.005);
  EXPECT_LT(e.tail<3>().norm(), 0.2 * kDegToRad);
}

TEST(KeyframeStructure, MarginalisingTheKeyframeFoldsItsLinksAndAFrameDropsItsOwn) {
  // Keyframe 0 with tight links to frames 1 and 2. Removing frame 1 (front)
  // drops its link and leaves the other; removing the keyframe folds its
  // links into a prior over the frames it linked.
  const auto& fx = fixture();
  Window w;
  w.T_b_c = fx.rectifier().T_b_rect(0);
  w.gauge = Gauge::kPose;
  const auto state = [&](std::size_t k) {
    imu::NavState x;
    x.R_w_b = fx.path()[k].T_w_b.so3();
    x.p_w = fx.path()[k].T_w_b.translation();
    return x;
  };
  const std::size_t samples[] = {900, 910, 920, 930};
  w.states.push_back({1, state(samples[0]), 0.0, Vec3::Zero(), sceneAt(samples[0], 100).points});
  for (std::size_t k = 1; k < 4; ++k) {
    w.states.push_back({static_cast<std::int64_t>(k + 1), state(samples[k]), 0.0, Vec3::Zero(), {}});
    w.visual.push_back({0, k, RelativePoseLink{}, std::make_shared<const vision::EdgePyramid>(pyramidAt(samples[k]))});
  }
  const EstimatorOptions o;
  Window front = w;
  marginalize(&front, 1, o);
  ASSERT_EQ(front.visual.size(), 2u);
  EXPECT_EQ(front.visual[0].n, 1u);
  EXPECT_EQ(front.visual[1].n, 2u);
  EXPECT_TRUE(front.prior.empty());  // a state with no inertial link and its visual link dropped leaves nothing
  Window back = w;
  marginalize(&back, 0, o);
  EXPECT_TRUE(back.visual.empty());
  ASSERT_EQ(back.prior.states.size(), 3u);
  // The folded links tie the frames together: the prior has off-diagonal blocks.
  EXPECT_GT((back.prior.H.block<6, 6>(0, 15).norm()), 1.0);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(back.prior.H);
  EXPECT_GT(eig.eigenvalues().minCoeff(), -1e-6 * eig.eigenvalues().maxCoeff());
}

}  // namespace
}  // namespace edgevio::estimator
