// Edge alignment: analytic Jacobians against numeric differentiation, and
// accuracy on rendered frames with known motion.
#include "edgevio/tracking/edge_alignment.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <cmath>

#include "common/render_fixture.h"
#include "common/test_support.h"
#include "edgevio/vision/keyframe_depth.h"

namespace edgevio::tracking {
namespace {

using geometry::SE3;
using geometry::SO3;

vision::LevelCamera testCamera() { return {220.0, 219.0, 185.0, 121.0, 376, 240}; }

TEST(EdgeAlignment, ProjectionJacobianMatchesNumeric) {
  const vision::LevelCamera cam = testCamera();
  const SE3 T(SO3::exp(Vec3(0.1, -0.2, 0.05)), Vec3(0.1, 0.05, -0.2));
  for (const Vec3& P : {Vec3(0.3, -0.2, 2.0), Vec3(-1.0, 0.4, 3.5), Vec3(0.0, 0.0, 1.0)}) {
    Vec2 uv;
    Jacobian26 J;
    ASSERT_TRUE(projectWithJacobian(P, T, cam, &uv, &J));
    const auto f = [&](const Eigen::VectorXd& xi) -> Eigen::VectorXd {
      Vec2 p;
      projectWithJacobian(P, T * SE3::exp(Vec6(xi)), cam, &p, nullptr);
      return p;
    };
    test::expectJacobianNear(J, test::numericJacobian(f, Eigen::VectorXd::Zero(6), 1e-7), 1e-4, "d(u,v)/dxi");
  }
}

TEST(EdgeAlignment, ResidualJacobianMatchesNumericOnALinearField) {
  // On an edge map whose distance transform is linear (a single straight edge
  // far away), bilinear sampling and central differences are exact, so the
  // chain ∇V·∂π/∂P·∂P/∂ξ must match numeric differentiation closely.
  cv::Mat edges = cv::Mat::zeros(240, 376, CV_8UC1);
  edges.col(0).setTo(255);  // V(u, v) = u
  const vision::DistanceTransform dt(edges);
  const vision::LevelCamera cam = testCamera();
  const SE3 T(SO3::exp(Vec3(0.02, -0.03, 0.01)), Vec3(0.05, 0.02, 0.1));
  for (const Vec3& P : {Vec3(0.3, -0.2, 2.0), Vec3(-0.5, 0.3, 3.0), Vec3(0.6, 0.1, 2.5)}) {
    double r;
    Jacobian16 J;
    ASSERT_TRUE(edgeResidual(P, T, cam, dt, 2, &r, &J));
    const auto f = [&](const Eigen::VectorXd& xi) -> Eigen::VectorXd {
      double v;
      edgeResidual(P, T * SE3::exp(Vec6(xi)), cam, dt, 2, &v, nullptr);
      return Eigen::VectorXd::Constant(1, v);
    };
    // V is stored as float (resolution ~2e-5 at V ≈ 200 px), so the step must
    // move the projection by much more than that: h = 1e-3 moves it ~0.2 px.
    // The remaining error is the projection's curvature, O(h·|∂²u/∂ξ²|) < 0.5.
    test::expectJacobianNear(J, test::numericJacobian(f, Eigen::VectorXd::Zero(6), 1e-3), 0.5, "d r/dxi");
  }
}

struct AlignmentCase {
  SE3 truth;  ///< T_nr, reference camera → current camera
  AlignmentResult result;
  int reference_points = 0;
};

/// Renders the keyframe at path sample i and the current frame `frames` camera
/// frames (50 ms each) later, aligns from `init` (identity if null).
AlignmentCase alignAlongPath(const test::RenderFixture& fx, std::size_t i, int frames, const SE3* init = nullptr,
                             const RotationPrior* rotation_prior = nullptr) {
  const auto& path = fx.path();
  const std::size_t j = i + static_cast<std::size_t>(frames) * 10;  // 200 Hz samples
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  const StereoFrame ref = fx.frame(path[i].T_w_b, 0, i), cur = fx.frame(path[j].T_w_b, 1, j);
  const vision::VisionOptions vo;
  const AlignmentOptions ao;
  const vision::EdgePyramid ref_pyr = vision::buildEdgePyramid(ref.left, fx.rectifier().rectifiedCamera(), vo);
  const vision::KeyframeDepth depth = vision::computeKeyframeDepth(ref_pyr, ref.right.get(), fx.rectifier().baseline(), vo);
  const vision::EdgePyramid cur_pyr = vision::buildEdgePyramid(cur.left, fx.rectifier().rectifiedCamera(), vo);
  AlignmentCase c;
  c.truth = (path[j].T_w_b * T_b_c).inverse() * (path[i].T_w_b * T_b_c);
  c.result = alignEdges(depth.points, cur_pyr, init ? *init : SE3(), ao, -1, 0, rotation_prior);
  c.reference_points = static_cast<int>(depth.points[0].size());
  return c;
}

void errors(const AlignmentCase& c, double* trans_m, double* rot_deg) {
  const SE3 E = c.truth.inverse() * c.result.T_nr;
  *trans_m = E.translation().norm();
  *rot_deg = geometry::angle(E.so3()) * 180.0 / 3.14159265358979;
}

const test::RenderFixture& fixture() {
  static const test::RenderFixture f("figure8", 14.0);
  return f;
}

/// Worst error over poses along the path whose keyframe has enough reference
/// points to constrain a pose (views of nearly blank surfaces are left to the
/// self check and the keyframe policy, tested elsewhere).
void worstErrorAlongPath(int frames, double* worst_t, double* worst_r, int* tested) {
  constexpr int kMinReferencePoints = 2000;
  *worst_t = *worst_r = 0.0;
  *tested = 0;
  for (std::size_t i = 500; i + static_cast<std::size_t>(frames) * 10 < 2600; i += 260) {
    const AlignmentCase c = alignAlongPath(fixture(), i, frames);
    double t, r;
    errors(c, &t, &r);
    const bool used = c.reference_points >= kMinReferencePoints;
    std::printf("  %d frame(s) from sample %zu: motion %.3f m %.2f deg, %d reference points%s -> error %.4f m %.3f deg\n",
                frames, i, c.truth.translation().norm(), geometry::angle(c.truth.so3()) * 57.2958, c.reference_points,
                used ? "" : " (too few, not counted)", t, r);
    if (!used) continue;
    EXPECT_TRUE(c.result.self_check_passed) << "sample " << i;
    *worst_t = std::max(*worst_t, t);
    *worst_r = std::max(*worst_r, r);
    ++*tested;
  }
}

TEST(EdgeAlignment, OneFrameApartIsAccurate) {
  double t, r;
  int n;
  worstErrorAlongPath(1, &t, &r, &n);
  std::printf("one frame apart: worst %.4f m, %.4f deg over %d poses\n", t, r, n);
  // Issue #5 asks for 5 mm / 0.1 deg; the method achieves 1.9 mm / 0.034 deg
  // here, so the bounds are tightened to that with a margin for other scenes.
  EXPECT_GE(n, 5);
  EXPECT_LT(t, 0.003);
  EXPECT_LT(r, 0.06);
}

TEST(EdgeAlignment, FiveFramesApartFromIdentity) {
  double t, r;
  int n;
  worstErrorAlongPath(5, &t, &r, &n);
  std::printf("five frames apart from identity: worst %.4f m, %.4f deg over %d poses\n", t, r, n);
  // Issue #5: 2 cm / 0.5 deg. Achieved 5.8 mm / 0.13 deg with reference points
  // on Canny's pixels, 6.9 mm / 0.15 deg with them on the sub-pixel edge (which
  // lowers the median link error on the EuRoC renders by 11-20 %, but not here):
  // bounds at half the issue's.
  EXPECT_GE(n, 5);
  EXPECT_LT(t, 0.01);
  EXPECT_LT(r, 0.25);
}

constexpr double kDeg = 3.14159265358979323846 / 180.0;

TEST(EdgeAlignment, AStiffRotationPriorHoldsTheRotationFiveFramesApart) {
  // The prior's residual is Log(R_priorᵀ R) with information 1/σ² per level-0
  // pixel of edge noise; at σ = 1e-3 deg it outweighs the ~2000 edge points
  // by far, so the result's rotation must sit on the prior, even a prior
  // 0.3 deg off the truth (a sign error would push it away instead), and the
  // translation absorbs what is left.
  int tested = 0;
  for (std::size_t i = 500; i < 2500; i += 520) {
    const AlignmentCase free = alignAlongPath(fixture(), i, 5);
    const SO3 R_truth = free.truth.so3();
    const RotationPrior prior{R_truth * SO3::exp(Vec3(0.3, -0.2, 0.1).normalized() * 0.3 * kDeg), 1e-3 * kDeg};
    const AlignmentCase held = alignAlongPath(fixture(), i, 5, nullptr, &prior);
    const double off_prior = geometry::angle(prior.R_nr.inverse() * held.result.T_nr.so3()) / kDeg;
    std::printf("  sample %zu: without prior %.3f deg off the truth; with it %.4f deg off the prior\n", i,
                geometry::angle(R_truth.inverse() * free.result.T_nr.so3()) / kDeg, off_prior);
    EXPECT_LT(off_prior, 0.01) << "sample " << i;
    ++tested;
  }
  EXPECT_GE(tested, 3);
}

TEST(EdgeAlignment, ARotationPriorAtTheTruthMakesLinksFiveFramesApartNoWorse) {
  // A prior where a perfect gyroscope puts it (at the truth, σ = 0.05 deg,
  // the default) adds information: the links must keep the bounds of
  // FiveFramesApartFromIdentity and their mean errors must not grow.
  double worst_t = 0.0, worst_r = 0.0, sum[2][2] = {};
  int n = 0;
  for (std::size_t i = 500; i + 50 < 2600; i += 260) {
    const AlignmentCase free = alignAlongPath(fixture(), i, 5);
    if (free.reference_points < 2000) continue;
    const RotationPrior prior{free.truth.so3(), 0.05 * kDeg};
    const AlignmentCase held = alignAlongPath(fixture(), i, 5, nullptr, &prior);
    double t, r;
    errors(free, &t, &r);
    sum[0][0] += t;
    sum[0][1] += r;
    errors(held, &t, &r);
    sum[1][0] += t;
    sum[1][1] += r;
    worst_t = std::max(worst_t, t);
    worst_r = std::max(worst_r, r);
    ++n;
  }
  std::printf("five frames apart: mean error %.4f m %.4f deg without the prior, %.4f m %.4f deg with it; worst with it %.4f m %.4f deg\n",
              sum[0][0] / n, sum[0][1] / n, sum[1][0] / n, sum[1][1] / n, worst_t, worst_r);
  EXPECT_GE(n, 5);
  EXPECT_LT(worst_t, 0.01);
  EXPECT_LT(worst_r, 0.25);
  EXPECT_LE(sum[1][0], sum[0][0]);
  EXPECT_LE(sum[1][1], sum[0][1]);
}

TEST(EdgeAlignment, TheSelfCheckRefusesAFitThatPinsOnlyARay) {
  // Reference points gathered in one small patch of the image lie on their
  // edges at the true pose (small mean distance, all visible) but fix little
  // more than the ray to the patch: a step δz along it only rescales the patch,
  // moving its points by extent·δz/Z pixels (8 px·δz/2 m here), and rotation
  // absorbs the rest; the whole view fixes the translation to millimetres.
  // The self check must tell the two apart by the translation's σ.
  const auto& fx = fixture();
  const std::size_t i = 1300, j = i + 10;
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  const StereoFrame ref = fx.frame(fx.path()[i].T_w_b, 0, i), cur = fx.frame(fx.path()[j].T_w_b, 1, j);
  const vision::VisionOptions vo;
  const vision::EdgePyramid ref_pyr = vision::buildEdgePyramid(ref.left, fx.rectifier().rectifiedCamera(), vo);
  const vision::KeyframeDepth depth = vision::computeKeyframeDepth(ref_pyr, ref.right.get(), fx.rectifier().baseline(), vo);
  const vision::EdgePyramid cur_pyr = vision::buildEdgePyramid(cur.left, fx.rectifier().rectifiedCamera(), vo);
  const SE3 truth = (fx.path()[j].T_w_b * T_b_c).inverse() * (fx.path()[i].T_w_b * T_b_c);
  const std::vector<Eigen::Vector3f>& all = depth.points[0];
  ASSERT_GE(all.size(), 1000u);
  // The patch: level-0 points within 8 px (in the keyframe's image) of the middle point.
  const vision::LevelCamera& c = ref_pyr.levels[0].camera;
  const auto pixel = [&](const Eigen::Vector3f& P) { return Vec2(c.fx * P.x() / P.z() + c.cx, c.fy * P.y() / P.z() + c.cy); };
  const Vec2 centre = pixel(all[all.size() / 2]);
  std::vector<Eigen::Vector3f> patch;
  for (const Eigen::Vector3f& P : all)
    if ((pixel(P) - centre).norm() <= 8.0) patch.push_back(P);
  ASSERT_GE(patch.size(), 30u);  // alignment's min_points
  const AlignmentOptions ao;
  const AlignmentResult whole = alignEdges({all}, cur_pyr, truth, ao);
  const AlignmentResult pinned = alignEdges({patch}, cur_pyr, truth, ao);
  std::printf("whole view: %zu points, mean distance %.2f px, translation sigma %.4f m; one patch: %zu points, %.2f px, %.3f m\n",
              all.size(), whole.mean_distance_px, whole.translation_sigma_m, patch.size(), pinned.mean_distance_px,
              pinned.translation_sigma_m);
  EXPECT_TRUE(whole.self_check_passed);
  EXPECT_LT(whole.translation_sigma_m, ao.self_check_max_translation_sigma_m / 10);
  // The patch passes every other test of the self check...
  EXPECT_LT(pinned.mean_distance_px, ao.self_check_max_mean_distance_px);
  EXPECT_GE(pinned.visible_ratio, ao.self_check_min_visible_ratio);
  // ...and fails on its σ alone.
  EXPECT_GT(pinned.translation_sigma_m, ao.self_check_max_translation_sigma_m);
  EXPECT_FALSE(pinned.self_check_passed);
}

}  // namespace
}  // namespace edgevio::tracking
