// When a run declares its estimate lost, and when it trusts it again.
#include "edgevio/pipeline/loss_monitor.h"

#include <gtest/gtest.h>

#include <limits>

namespace edgevio::pipeline {
namespace {

FrameRecord frame(int k, bool passed) {
  FrameRecord r;
  r.t_ns = 1000000000LL + k * 50000000LL;
  r.aligned = k > 0;
  r.alignment.self_check_passed = passed;
  return r;
}

TEST(LossMonitor, ConsecutiveFailuresLoseTheEstimateFromTheFirstUntilTrackedAgain) {
  LossMonitor m(3);
  std::vector<FrameRecord> r;
  // Frame 0 is a first frame; 2-3 fail (two: not lost); 5-9 fail; 10 tracks again.
  for (int k = 0; k <= 11; ++k) r.push_back(frame(k, !(k == 2 || k == 3 || (k >= 5 && k <= 9))));
  for (FrameRecord& x : r) m.update(&x);
  for (int k = 0; k <= 11; ++k) {
    const bool lost = k >= 7 && k <= 9;  // declared at the third failure (7), until frame 10 tracks
    EXPECT_EQ(r[k].status == TrackingStatus::kLost, lost) << k;
    EXPECT_EQ(r[k].lost_since_ns >= 0, k == 7) << k;
  }
  EXPECT_EQ(r[7].lost_since_ns, r[5].t_ns);  // its first symptom
  EXPECT_EQ(r[7].lost_reason, "3 consecutive self-check failures");
}

TEST(LossMonitor, ANonFinitePoseIsLostAtOnce) {
  LossMonitor m(10);
  FrameRecord ok = frame(1, true), bad = frame(2, true), again = frame(3, true);
  bad.T_w_b = geometry::SE3(geometry::SO3(), Vec3(std::numeric_limits<double>::quiet_NaN(), 0, 0));
  m.update(&ok);
  m.update(&bad);
  m.update(&again);
  EXPECT_EQ(ok.status, TrackingStatus::kOk);
  EXPECT_EQ(bad.status, TrackingStatus::kLost);
  EXPECT_EQ(bad.lost_since_ns, bad.t_ns);
  EXPECT_EQ(bad.lost_reason, "non-finite pose");
  EXPECT_EQ(again.status, TrackingStatus::kOk);
}

}  // namespace
}  // namespace edgevio::pipeline
