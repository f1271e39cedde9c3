#include "edgevio/pipeline/loss_monitor.h"

#include <string>

namespace edgevio::pipeline {

void LossMonitor::update(FrameRecord* r) {
  const bool failed = r->aligned && !r->selfCheckPassed();
  if (failed) {
    if (failures_ == 0) first_failure_ns_ = r->t_ns;
    ++failures_;
  } else if (r->aligned) {
    failures_ = 0;
    lost_ = false;  // tracked again
  }
  const auto begin = [&](std::int64_t since, std::string why) {
    lost_ = true;
    r->lost_since_ns = since;
    r->lost_reason = std::move(why);
  };
  if (!r->T_w_b.translation().allFinite() || !r->T_w_b.so3().matrix().allFinite()) {
    if (!lost_) begin(r->t_ns, "non-finite pose");
  } else if (failed && failures_ >= lost_after_ && !lost_) {
    begin(first_failure_ns_, std::to_string(failures_) + " consecutive self-check failures");
  }
  r->status = lost_ ? TrackingStatus::kLost : TrackingStatus::kOk;
}

}  // namespace edgevio::pipeline
