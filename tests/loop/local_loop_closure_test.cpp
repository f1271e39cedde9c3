// Local loop closure (METHOD.md §6) on rendered keyframes of the figure8
// room: a revisit of a place from a drifted estimate is accepted and
// measured to the accuracy of edge alignment; a different place that the
// estimates claim is the same (drift, or similar texture) fails the cross
// check and yields no link.
#include "edgevio/loop/local_loop_closure.h"

#include <gtest/gtest.h>

#include <limits>

#include <cstdio>

#include "common/render_fixture.h"

namespace edgevio::loop {
namespace {

using geometry::SE3;
using geometry::SO3;

constexpr double kNoBudget = std::numeric_limits<double>::infinity();


std::shared_ptr<const tracking::KeyframeData> keyframe(const test::RenderFixture& fx, const SE3& T_w_b, std::int64_t t) {
  return fx.keyframe(T_w_b, t, static_cast<std::uint64_t>(t));
}

TEST(LocalLoopClosure, AcceptsARevisitAndRejectsADifferentPlace) {
  const test::RenderFixture fx;
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  LoopOptions lo;
  lo.skip_recent_keyframes = 0;  // a single older keyframe here
  const tracking::AlignmentOptions ao;
  // The place, seen first at path sample 1400 and again later from 12 cm and 4 deg away.
  const SE3 T_w_b_first = fx.path()[1400].T_w_b;
  const SE3 T_w_b_again = T_w_b_first * SE3(SO3::exp(Vec3(0.0, 4.0 * kPi / 180, 0.0)), Vec3(0.08, -0.05, 0.07));
  const auto first = keyframe(fx, T_w_b_first, 1);
  const auto again = keyframe(fx, T_w_b_again, 2);
  // The estimate of the revisit has drifted by 4 cm and 1.5 deg.
  const SE3 drift(SO3::exp(Vec3(0.0, 0.0, 1.5 * kPi / 180)), Vec3(0.03, -0.02, 0.02));
  LoopStats stats;
  const std::vector<LoopLink> links =
      closeLoops({again, drift * T_w_b_again * T_b_c}, {{first, T_w_b_first * T_b_c}}, lo, ao, kNoBudget, &stats);
  std::printf("revisit: %d candidates, %d coarse, %d full, %d accepted, %.1f ms\n", stats.candidates, stats.coarse_attempts,
              stats.full_attempts, stats.accepted, stats.ms);
  ASSERT_EQ(links.size(), 1u);
  const SE3 truth = (T_w_b_again * T_b_c).inverse() * (T_w_b_first * T_b_c);
  const SE3 E = truth.inverse() * links[0].T_nr;
  std::printf("loop link error: %.4f m, %.4f deg\n", E.translation().norm(), geometry::angle(E.so3()) * 180 / kPi);
  // Edge alignment's accuracy on renders (tracking tests: 2-4 mm, < 0.08 deg).
  EXPECT_LT(E.translation().norm(), 0.01);
  EXPECT_LT(geometry::angle(E.so3()) * 180 / kPi, 0.2);

  // Different places with the same kind of texture (the room's other walls),
  // whose drifted estimates put them where the first keyframe is.
  int rejected = 0, tried = 0;
  for (std::size_t sample : {200u, 600u, 1000u, 1800u, 2200u}) {
    const SE3 T_w_b_other = fx.path()[sample].T_w_b;
    const SE3 T_rel = T_w_b_first.inverse() * T_w_b_other;
    if (T_rel.translation().norm() < 0.5 && geometry::angle(T_rel.so3()) < 30 * kPi / 180) continue;  // really elsewhere
    const auto other = keyframe(fx, T_w_b_other, 10 + static_cast<std::int64_t>(sample));
    const std::vector<LoopLink> wrong =
        closeLoops({other, T_w_b_first * SE3(SO3(), Vec3(0.02, 0, 0)) * T_b_c}, {{first, T_w_b_first * T_b_c}}, lo, ao, kNoBudget, &stats);
    ++tried;
    rejected += wrong.empty();
    std::printf("different place (sample %zu, %.2f m, %.0f deg away): %s (%d coarse, %d cross-check failures)\n", sample,
                T_rel.translation().norm(), geometry::angle(T_rel.so3()) * 180 / kPi, wrong.empty() ? "rejected" : "ACCEPTED",
                stats.coarse_attempts, stats.cross_check_failures);
  }
  EXPECT_GE(tried, 3);
  EXPECT_EQ(rejected, tried);
}

TEST(LocalLoopClosure, GatesCandidatesByDistanceAndViewingDirection) {
  const test::RenderFixture fx;
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  const SE3 T = fx.path()[1400].T_w_b * T_b_c;
  const auto k = keyframe(fx, fx.path()[1400].T_w_b, 1);
  const auto k2 = keyframe(fx, fx.path()[1400].T_w_b, 2);
  const double depth = medianDepth(*k2);
  ASSERT_GT(depth, 0.5);
  LoopOptions lo;
  lo.skip_recent_keyframes = 0;
  LoopStats stats;
  // Farther than max_distance_depth_ratio × depth, or turned beyond max_view_angle_deg: no candidate.
  closeLoops({k2, T * SE3(SO3(), Vec3(1.1 * lo.max_distance_depth_ratio * depth, 0, 0))}, {{k, T}}, lo, {}, kNoBudget, &stats);
  EXPECT_EQ(stats.candidates, 0);
  closeLoops({k2, T * SE3(SO3::exp(Vec3(0, 1.1 * lo.max_view_angle_deg * kPi / 180, 0)), Vec3::Zero())}, {{k, T}}, lo, {}, kNoBudget, &stats);
  EXPECT_EQ(stats.candidates, 0);
  closeLoops({k2, T}, {{k, T}}, lo, {}, kNoBudget, &stats);
  EXPECT_EQ(stats.candidates, 1);
}

}  // namespace
}  // namespace edgevio::loop
