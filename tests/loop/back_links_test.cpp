// Back links (loop/back_links.h) on rendered keyframes of the figure8 room:
// a new keyframe's points aligned into the two keyframes before it measure
// the motion to the accuracy of edge alignment, from estimates that have
// drifted a little; an estimate that disagrees with the alignment by more
// than the thresholds yields no link.
#include "edgevio/loop/back_links.h"

#include <gtest/gtest.h>

#include <cstdio>

#include "common/render_fixture.h"

namespace edgevio::loop {
namespace {

using geometry::SE3;
using geometry::SO3;

constexpr double kDeg = kDegToRad;

std::shared_ptr<const tracking::KeyframeData> keyframe(const test::RenderFixture& fx, std::size_t sample) {
  return fx.keyframe(fx.path()[sample].T_w_b, static_cast<std::int64_t>(sample), sample);
}

TEST(BackLinks, MeasureTheMotionBackToTheTwoKeyframesBefore) {
  const test::RenderFixture fx;
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  const tracking::AlignmentOptions ao;
  const BackLinkOptions bo;
  ASSERT_EQ(bo.keyframes, 2);
  // Keyframes 3 frames (150 ms) apart; the older estimates have drifted by
  // 1-2 cm and 0.3-0.5 deg, inside max_disagreement (5 cm, 1.5 deg).
  const std::size_t samples[] = {1200, 1230, 1260};
  const SE3 drift[] = {SE3(SO3::exp(Vec3(0.0, 0.5, 0.0) * kDeg), Vec3(0.02, 0.0, -0.01)),
                       SE3(SO3::exp(Vec3(0.3, 0.0, 0.0) * kDeg), Vec3(0.0, 0.01, 0.0))};
  const LoopKeyframe latest{keyframe(fx, samples[2]), fx.path()[samples[2]].T_w_b * T_b_c};
  const std::vector<LoopKeyframe> previous = {{keyframe(fx, samples[1]), fx.path()[samples[1]].T_w_b * T_b_c * drift[1]},
                                              {keyframe(fx, samples[0]), fx.path()[samples[0]].T_w_b * T_b_c * drift[0]}};
  BackLinkStats stats;
  const std::vector<LoopLink> links = backLinks(latest, previous, bo, ao, &stats);
  ASSERT_EQ(links.size(), 2u) << stats.self_check_failures << " self-check failures, " << stats.disagreements << " disagreements";
  for (std::size_t i = 0; i < 2; ++i) {
    const std::size_t older = samples[1 - i];
    EXPECT_EQ(links[i].t_ref_ns, static_cast<std::int64_t>(samples[2]));
    EXPECT_EQ(links[i].t_new_ns, static_cast<std::int64_t>(older));
    // T_nr maps the latest keyframe's camera into the older one's.
    const SE3 truth = (fx.path()[older].T_w_b * T_b_c).inverse() * (fx.path()[samples[2]].T_w_b * T_b_c);
    const SE3 E = truth.inverse() * links[i].T_nr;
    std::printf("back link to sample %zu (%.3f m, %.1f deg of motion): error %.4f m, %.3f deg\n", older,
                truth.translation().norm(), geometry::angle(truth.so3()) / kDeg, E.translation().norm(),
                geometry::angle(E.so3()) / kDeg);
    // Edge alignment's accuracy on these renders (five frames apart: < 1 cm, 0.25 deg).
    EXPECT_LT(E.translation().norm(), 0.01);
    EXPECT_LT(geometry::angle(E.so3()) / kDeg, 0.25);
  }
  BackLinkOptions off = bo;
  off.keyframes = 0;
  EXPECT_TRUE(backLinks(latest, previous, off, ao).empty());
}

TEST(BackLinks, AnEstimateFarFromTheAlignmentYieldsNoLink) {
  // The alignment converges to the truth from an estimate 8 cm off; that it
  // lands 8 cm from the estimate is what a wrong minimum looks like, so the
  // link is refused (the window keeps its tracking link).
  const test::RenderFixture fx;
  const SE3 T_b_c = fx.rectifier().T_b_rect(0);
  const LoopKeyframe latest{keyframe(fx, 1260), fx.path()[1260].T_w_b * T_b_c};
  const std::vector<LoopKeyframe> previous = {
      {keyframe(fx, 1230), fx.path()[1230].T_w_b * T_b_c * SE3(SO3(), Vec3(0.08, 0.0, 0.0))}};
  BackLinkStats stats;
  EXPECT_TRUE(backLinks(latest, previous, BackLinkOptions{}, tracking::AlignmentOptions{}, &stats).empty());
  EXPECT_EQ(stats.attempts, 1);
  EXPECT_EQ(stats.disagreements, 1);
}

}  // namespace
}  // namespace edgevio::loop
