// Edge alignment: analytic Jacobians against numeric differentiation, and
// accuracy on rendered frames with known motion.
#include "edgevio/tracking/edge_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

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

TEST(EdgeAlignment, MappedEdgeNormalMatchesNumeric) {
  // The image of a short step along the reference edge's tangent, at the
  // point's depth, is the tangent in the current image; the normal is it
  // turned by −90°, so that it keeps the gradient's sign.
  const vision::LevelCamera cam = testCamera();
  const SE3 T(SO3::exp(Vec3(0.1, -0.2, 0.3)), Vec3(0.1, 0.05, -0.2));
  const auto pixel = [&](const Vec3& P) {
    const Vec3 Q = T * P;
    return Vec2(cam.fx * Q.x() / Q.z() + cam.cx, cam.fy * Q.y() / Q.z() + cam.cy);
  };
  for (const Vec3& P : {Vec3(0.3, -0.2, 2.0), Vec3(-1.0, 0.4, 3.5), Vec3(0.0, 0.0, 1.0)})
    for (const double a : {0.3, 2.0, -2.5}) {
      const Vec2 n(std::cos(a), std::sin(a));
      const double h = 1e-4;  // keyframe pixels along the tangent (−n_y, n_x)
      const Vec3 dP(-n.y() * P.z() / cam.fx, n.x() * P.z() / cam.fy, 0.0);
      const Vec2 tau = (pixel(P + h * dP) - pixel(P - h * dP)).normalized();
      const Vec2 numeric(tau.y(), -tau.x());
      EXPECT_LT((mapEdgeNormal(P, n, T, cam) - numeric).norm(), 1e-6) << "P " << P.transpose() << ", angle " << a;
    }
  // Turning the camera by φ about its optical axis (fx = fy, centred) turns
  // the image, and every normal, by φ.
  const vision::LevelCamera square{200.0, 200.0, 187.5, 119.5, 376, 240};
  const double phi = 0.4;
  const SE3 roll(SO3::exp(Vec3(0, 0, phi)), Vec3::Zero());
  const Vec2 n = Vec2(1.0, 2.0).normalized();
  const Vec2 turned(std::cos(phi) * n.x() - std::sin(phi) * n.y(), std::sin(phi) * n.x() + std::cos(phi) * n.y());
  EXPECT_LT((mapEdgeNormal(Vec3(0.4, -0.3, 2.0), n, roll, square) - turned).norm(), 1e-9);
}

struct AlignmentCase {
  SE3 truth;  ///< T_nr, reference camera → current camera
  AlignmentResult result;
  int reference_points = 0;
};

/// Renders the keyframe at path sample i and the current frame `frames` camera
/// frames (50 ms each) later, aligns from `init` (identity if null).
AlignmentCase alignAlongPath(const test::RenderFixture& fx, std::size_t i, int frames, const SE3* init = nullptr,
                             const RotationPrior* rotation_prior = nullptr, const AlignmentOptions& ao = AlignmentOptions{}) {
  const auto& path = fx.path();
  const std::size_t j = i + static_cast<std::size_t>(frames) * 10;  // 200 Hz samples
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  const StereoFrame ref = fx.frame(path[i].T_w_b, 0, i), cur = fx.frame(path[j].T_w_b, 1, j);
  const vision::VisionOptions vo;
  const vision::EdgePyramid ref_pyr = vision::buildEdgePyramid(ref.left, fx.rectifier().rectifiedCamera(), vo);
  const vision::KeyframeDepth depth = vision::computeKeyframeDepth(ref_pyr, ref.right.get(), fx.rectifier().baseline(), vo);
  const vision::EdgePyramid cur_pyr = vision::buildEdgePyramid(cur.left, fx.rectifier().rectifiedCamera(), vo);
  AlignmentCase c;
  c.truth = (path[j].T_w_b * T_b_c).inverse() * (path[i].T_w_b * T_b_c);
  c.result = alignEdges(depth, cur_pyr, init ? *init : SE3(), ao, -1, 0, rotation_prior);
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
  // Issue #5 asks for 5 mm / 0.1 deg; the method achieved 1.9 mm / 0.034 deg
  // here (1.3 mm / 0.024 deg since the normal check and the discontinuity
  // test), so the bounds are tightened to that with a margin for other scenes.
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
  // lowers the median link error on the EuRoC renders by 11-20 %, but not here),
  // 3.8 mm / 0.091 deg with the normal check and the discontinuity test (which
  // lower it by a further 29 %): bounds at half the issue's.
  EXPECT_GE(n, 5);
  EXPECT_LT(t, 0.01);
  EXPECT_LT(r, 0.25);
}

constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// Five frames apart along the path, views with enough reference points:
/// `variant` (given the true motion) must keep the bounds of
/// FiveFramesApartFromIdentity, and its mean errors must not exceed those of
/// `baseline`.
void expectFiveFramesApartNoWorse(const char* what, const std::function<AlignmentCase(std::size_t)>& baseline,
                                  const std::function<AlignmentCase(std::size_t, const SE3&)>& variant) {
  double worst_t = 0.0, worst_r = 0.0, sum[2][2] = {};
  int n = 0;
  for (std::size_t i = 500; i + 50 < 2600; i += 260) {
    const AlignmentCase base = baseline(i);
    if (base.reference_points < 2000) continue;
    const AlignmentCase var = variant(i, base.truth);
    double t, r;
    errors(base, &t, &r);
    sum[0][0] += t;
    sum[0][1] += r;
    errors(var, &t, &r);
    sum[1][0] += t;
    sum[1][1] += r;
    worst_t = std::max(worst_t, t);
    worst_r = std::max(worst_r, r);
    ++n;
  }
  std::printf("five frames apart: mean error %.4f m %.4f deg without %s, %.4f m %.4f deg with it; worst with it %.4f m %.4f deg\n",
              sum[0][0] / n, sum[0][1] / n, what, sum[1][0] / n, sum[1][1] / n, worst_t, worst_r);
  EXPECT_GE(n, 5);
  EXPECT_LT(worst_t, 0.01);
  EXPECT_LT(worst_r, 0.25);
  EXPECT_LE(sum[1][0], sum[0][0]);
  EXPECT_LE(sum[1][1], sum[0][1]);
}

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
  expectFiveFramesApartNoWorse("the prior", [](std::size_t i) { return alignAlongPath(fixture(), i, 5); },
                               [](std::size_t i, const SE3& truth) {
                                 const RotationPrior prior{truth.so3(), 0.05 * kDeg};
                                 return alignAlongPath(fixture(), i, 5, nullptr, &prior);
                               });
}

TEST(EdgeAlignment, AtTheTruthReferenceEdgesMeetEdgesOfTheirOwnNormal) {
  // The normal check rests on this: at the true pose, the nearest edge of a
  // reference point is mostly its own edge, whose normal (with the gradient's
  // sign) the mapped reference normal matches; with the sign flipped, as for
  // the far side of a thin line, it mostly does not. Five frames apart in the
  // figure8 room, level 0.
  const auto& fx = fixture();
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  const vision::VisionOptions vo;
  const double min_cos = std::cos(AlignmentOptions{}.max_normal_angle_deg * 3.14159265358979 / 180.0);
  int tested = 0;
  for (std::size_t i = 500; i + 50 < 2600; i += 520) {
    const std::size_t j = i + 50;
    const StereoFrame ref = fx.frame(fx.path()[i].T_w_b, 0, i), cur = fx.frame(fx.path()[j].T_w_b, 1, j);
    const vision::EdgePyramid ref_pyr = vision::buildEdgePyramid(ref.left, fx.rectifier().rectifiedCamera(), vo);
    const vision::KeyframeDepth depth = vision::computeKeyframeDepth(ref_pyr, ref.right.get(), fx.rectifier().baseline(), vo);
    const vision::EdgePyramid cur_pyr = vision::buildEdgePyramid(cur.left, fx.rectifier().rectifiedCamera(), vo);
    const SE3 truth = (fx.path()[j].T_w_b * T_b_c).inverse() * (fx.path()[i].T_w_b * T_b_c);
    const vision::EdgeLevel& level = cur_pyr.levels[0];
    ASSERT_EQ(depth.normals[0].size(), depth.points[0].size());
    if (depth.points[0].size() < 2000) continue;  // a nearly blank view, as in worstErrorAlongPath
    int near = 0, same = 0, flipped = 0;
    for (std::size_t k = 0; k < depth.points[0].size(); ++k) {
      const Vec3 P = depth.points[0][k].cast<double>();
      Vec2 uv;
      if (!projectWithJacobian(P, truth, level.camera, &uv, nullptr)) continue;
      if (uv.x() < 2 || uv.y() < 2 || uv.x() > level.camera.width - 3 || uv.y() > level.camera.height - 3) continue;
      if (level.dt.value(uv.x(), uv.y()) > 1.0f) continue;  // not re-detected here
      Vec2 e, n;
      level.dt.nearestLine(uv.x(), uv.y(), &e, &n);
      const Vec2 n_ref = depth.normals[0][k].cast<double>();
      ++near;
      same += mapEdgeNormal(P, n_ref, truth, level.camera).dot(n) >= min_cos;
      flipped += mapEdgeNormal(P, -n_ref, truth, level.camera).dot(n) >= min_cos;
    }
    std::printf("  sample %zu: %d reference points within 1 px of an edge, %.1f %% of them match its normal, %.1f %% with the sign flipped\n",
                i, near, 100.0 * same / near, 100.0 * flipped / near);
    ASSERT_GE(near, 500);
    EXPECT_GT(same, 0.9 * near) << "sample " << i;
    EXPECT_LT(flipped, 0.1 * near) << "sample " << i;
    ++tested;
  }
  EXPECT_GE(tested, 3);
}

TEST(EdgeAlignment, TheNormalCheckMakesLinksFiveFramesApartNoWorse) {
  // Dropping points whose nearest edge is another edge removes a pull towards
  // the wrong place: mean errors five frames apart, from identity, must not
  // grow against the same alignment without the check, and the bounds of
  // FiveFramesApartFromIdentity hold.
  expectFiveFramesApartNoWorse(
      "the normal check",
      [](std::size_t i) {
        AlignmentOptions off;
        off.max_normal_angle_deg = 0.0;
        return alignAlongPath(fixture(), i, 5, nullptr, nullptr, off);
      },
      [](std::size_t i, const SE3&) { return alignAlongPath(fixture(), i, 5); });
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
  vision::KeyframeDepth whole_ref, patch_ref;
  whole_ref.points = {all};
  patch_ref.points = {patch};
  const AlignmentResult whole = alignEdges(whole_ref, cur_pyr, truth, ao);
  const AlignmentResult pinned = alignEdges(patch_ref, cur_pyr, truth, ao);
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
