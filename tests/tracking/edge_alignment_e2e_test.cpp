// Edge alignment on rendered frames with known motion along the figure8
// room: accuracy one and five frames apart, and what the rotation prior and
// the normal check do to it.
#include "edgevio/tracking/edge_alignment.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <functional>

#include "common/render_fixture.h"
#include "edgevio/vision/keyframe_depth.h"

namespace edgevio::tracking {
namespace {

using geometry::SE3;
using geometry::SO3;

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
  *rot_deg = geometry::angle(E.so3()) * kRadToDeg;
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
                frames, i, c.truth.translation().norm(), geometry::angle(c.truth.so3()) * kRadToDeg, c.reference_points,
                used ? "" : " (too few, not counted)", t, r);
    if (!used) continue;
    EXPECT_TRUE(c.result.self_check_passed) << "sample " << i;
    *worst_t = std::max(*worst_t, t);
    *worst_r = std::max(*worst_r, r);
    ++*tested;
  }
}

/// The worst error over the room's views `frames` apart, from identity, within the bounds.
void expectAccurateApart(int frames, double max_t, double max_r) {
  double t, r;
  int n;
  worstErrorAlongPath(frames, &t, &r, &n);
  std::printf("%d frame(s) apart from identity: worst %.4f m, %.4f deg over %d poses\n", frames, t, r, n);
  EXPECT_GE(n, 5);
  EXPECT_LT(t, max_t);
  EXPECT_LT(r, max_r);
}

// The front end's targets are 5 mm / 0.1 deg one frame apart and 2 cm /
// 0.5 deg five apart; the bounds are about 2.5 times the worst of this
// room's views (1.3 mm, 0.024 deg and 3.8 mm, 0.091 deg), inside the targets.
TEST(EdgeAlignment, OneFrameApartIsAccurate) { expectAccurateApart(1, 0.003, 0.06); }
TEST(EdgeAlignment, FiveFramesApartFromIdentity) { expectAccurateApart(5, 0.01, 0.25); }

constexpr double kDeg = kDegToRad;

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

}  // namespace
}  // namespace edgevio::tracking
