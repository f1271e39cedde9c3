#pragma once
// Whether the estimate can still be trusted, decided frame by frame from
// what the frame's record says. A loss is an interval, not the run's
// verdict: it begins at its first symptom and ends at the first frame
// tracked again.
//
// Signals: a run of tracking.lost_after_failures consecutive self-check
// failures (METHOD.md §3: the frames are dead-reckoned, and after that many
// the motion since the last good frame is beyond what the alignment's basin
// recovers), and a non-finite pose.
#include <cstdint>

#include "edgevio/pipeline/frame_record.h"

namespace edgevio::pipeline {

class LossMonitor {
 public:
  explicit LossMonitor(int lost_after_failures) : lost_after_(lost_after_failures) {}

  /// Sets r->status, and r->lost_since_ns and r->lost_reason where a loss begins.
  void update(FrameRecord* r);

 private:
  int lost_after_;
  int failures_ = 0;                ///< consecutive self-check failures
  std::int64_t first_failure_ns_ = -1;
  bool lost_ = false;
};

}  // namespace edgevio::pipeline
