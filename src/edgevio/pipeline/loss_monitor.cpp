#include "edgevio/pipeline/loss_monitor.h"

#include <algorithm>
#include <limits>
#include <string>

#include "edgevio/common/format.h"
#include "edgevio/common/time.h"

namespace edgevio::pipeline {

double LossMonitor::disagreementBound(std::int64_t t_ns) {
  // The accelerometer's prediction spans the last two intervals; its tolerance grows with their reach.
  double bound_m = std::numeric_limits<double>::infinity();
  if (disagreement_m_ > 0 && t_before_ns_ >= 0) {
    const double dt0 = toSeconds(t_prev_ns_ - t_before_ns_), dt1 = toSeconds(t_ns - t_prev_ns_);
    bound_m = disagreement_m_ + 0.5 * disagreement_mps2_ * dt1 * (dt0 + dt1);
  }
  t_before_ns_ = t_prev_ns_;
  t_prev_ns_ = t_ns;
  return bound_m;
}

void LossMonitor::update(FrameRecord* r) {
  const bool failed = r->aligned && (!r->selfCheckPassed() || r->frozen_image);
  const bool carried = r->state.has_value();  // the window's IMU state carried the frame
  // (without a gyroscope reading the disagreement is NaN and compares false)
  const bool contradicted = r->aligned && gyro_contradictions_ > 0 && gyro_disagreement_deg_ > 0 &&
                            r->gyro_disagreement_deg > gyro_disagreement_deg_;
  // (NaN, before a second or third frame, compares false)
  const bool too_fast = speed_mps_ > 0 && r->implied_speed_mps > speed_mps_;
  const double disagreement_bound_m = disagreementBound(r->t_ns);
  const bool unexplained = r->accel_disagreement_m > disagreement_bound_m;
  const bool implausible = (accel_mps2_ > 0 && r->implied_accel_mps2 > accel_mps2_) || too_fast || unexplained;
  if (r->aligned) {
    recent_.push_back({r->t_ns, contradicted, failed && !carried});
    if (recent_.size() > static_cast<std::size_t>(lost_after_)) recent_.pop_front();
  }
  const auto suspect = [](const Recent& f) { return f.contradicted || f.guessed; };
  int suspects = static_cast<int>(std::count_if(recent_.begin(), recent_.end(), suspect));
  if (failed) {
    if (failures_ == 0) first_failure_ns_ = r->t_ns;
    ++failures_;
  } else if (r->aligned) {
    failures_ = 0;
    // Tracked again; a loss the window of evidence declared needs that window to clear too.
    if (lost_ != Cause::kNone && !contradicted && !implausible &&
        (lost_ != Cause::kEvidence || suspects < gyro_contradictions_)) {
      lost_ = Cause::kNone;
      // A new loss needs new evidence: what was seen during this one is explained.
      recent_.clear();
      suspects = 0;
    }
  }
  const auto begin = [&](Cause cause, std::int64_t since, std::string why) {
    lost_ = cause;
    r->lost_since_ns = since;
    r->lost_reason = std::move(why);
  };
  if (!r->T_w_b.translation().allFinite() || !r->T_w_b.so3().matrix().allFinite()) {
    if (lost_ == Cause::kNone) begin(Cause::kFailures, r->t_ns, "non-finite pose");
  } else if (lost_ == Cause::kNone && r->frozen_image && !carried) {
    begin(Cause::kFailures, r->t_ns, "the image repeats the previous frame's to the last pixel (a stalled or blank camera)");
  } else if (lost_ == Cause::kNone && failed && failures_ >= lost_after_) {
    begin(Cause::kFailures, first_failure_ns_, std::to_string(failures_) + " consecutive self-check failures");
  } else if (lost_ == Cause::kNone && implausible) {
    begin(Cause::kImplausibleMotion, r->t_ns,
          too_fast      ? formatText("the pose's step implies a speed of %.0f m/s, over %.0f", r->implied_speed_mps, speed_mps_)
          : unexplained ? formatText("the pose lies %.2f m from the accelerometer's prediction, over %.2f",
                                     r->accel_disagreement_m, disagreement_bound_m)
                        : formatText("the pose's step implies an acceleration of %.0f m/s^2, over %.0f", r->implied_accel_mps2,
                                     accel_mps2_));
  } else if (lost_ == Cause::kNone && gyro_contradictions_ > 0 && r->aligned && !recent_.empty() && suspect(recent_.back()) &&
             suspects >= gyro_contradictions_) {
    const auto first = std::find_if(recent_.begin(), recent_.end(), suspect);
    const int contradictions =
        static_cast<int>(std::count_if(recent_.begin(), recent_.end(), [](const Recent& f) { return f.contradicted; }));
    begin(Cause::kEvidence, first->t_ns,
          contradictions == suspects
              ? formatText("the gyroscope contradicts %d of the last %zu frames' rotation by over %.1f deg", contradictions,
                       recent_.size(), gyro_disagreement_deg_)
              : formatText("%d of the last %zu frames failed the self check or their rotation is over %.1f deg from the gyroscope's",
                       suspects, recent_.size(), gyro_disagreement_deg_));
  }
  r->status = lost_ != Cause::kNone ? TrackingStatus::kLost : TrackingStatus::kOk;
}

}  // namespace edgevio::pipeline
