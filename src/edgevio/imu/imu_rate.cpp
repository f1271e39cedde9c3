#include "edgevio/imu/imu_rate.h"

#include <algorithm>

#include "edgevio/common/time.h"
#include "edgevio/imu/gyro_integration.h"

namespace edgevio::imu {

// The deltas alone: the noise densities only shape a covariance, which this does not carry.
ImuRatePropagator::ImuRatePropagator(double max_gap_s)
    : max_gap_s_(max_gap_s), pre_(Vec3::Zero(), Vec3::Zero(), ImuNoise{}, Propagation::kDeltasOnly) {}

void ImuRatePropagator::setEstimate(std::int64_t t_ns, const NavState& x) {
  if (t_ns <= t_estimate_) return;
  t_estimate_ = t_ns;
  estimate_ = x;
  pre_ = Preintegration(x.b_a, x.b_g, ImuNoise{}, Propagation::kDeltasOnly);
  t_integrated_ = t_ns;
  broken_ = false;
  // Keep the last reading at or before the estimate (to interpolate at its time) and those after.
  const auto after = std::upper_bound(recent_.begin(), recent_.end(), t_ns,
                                      [](std::int64_t t, const ImuSample& s) { return t < s.t_ns; });
  if (after != recent_.begin()) recent_.erase(recent_.begin(), after - 1);
  if (!recent_.empty() && recent_.back().t_ns > t_ns) integrateSince(t_ns);
}

void ImuRatePropagator::integrateSince(std::int64_t t0_ns) {
  const std::int64_t t1_ns = recent_.back().t_ns;
  if (imuGapWithin(recent_, t0_ns, t1_ns, max_gap_s_)) {
    broken_ = true;
    return;
  }
  if (forEachImuInterval(recent_, t0_ns, t1_ns, [&](double dt, const Vec3& a0, const Vec3& w0, const Vec3& a1, const Vec3& w1) {
        pre_.integrate(dt, a0, w0, a1, w1);
      }))
    t_integrated_ = t1_ns;
}

std::optional<NavState> ImuRatePropagator::propagate(const ImuSample& reading) {
  if (!recent_.empty() && reading.t_ns <= recent_.back().t_ns) return std::nullopt;  // out of order: ignored
  recent_.push_back(reading);
  if (t_estimate_ < 0) {
    // Before any estimate only the newest reading matters (the next estimate is later).
    recent_.erase(recent_.begin(), recent_.end() - 1);
    return std::nullopt;
  }
  // Readings older than kKeptSeconds go once integrated (a later estimate is
  // never that far behind), a second's worth at a time so that erasing from
  // the front stays rare.
  const std::int64_t keep_from = reading.t_ns - toNanoseconds(kKeptSeconds);
  if (recent_.front().t_ns < keep_from - toNanoseconds(1.0) && recent_.front().t_ns < t_integrated_) {
    const auto old_end = std::find_if(recent_.begin(), recent_.end(), [&](const ImuSample& s) {
      return s.t_ns >= keep_from || s.t_ns >= t_integrated_;
    });
    recent_.erase(recent_.begin(), old_end - 1);
  }
  if (broken_ || reading.t_ns <= t_estimate_) return std::nullopt;
  integrateSince(t_integrated_);
  if (broken_ || t_integrated_ != reading.t_ns) return std::nullopt;
  return predictState(estimate_, pre_);
}

}  // namespace edgevio::imu
