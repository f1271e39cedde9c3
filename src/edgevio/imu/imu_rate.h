#pragma once
// The pose a flight controller consumes between frames: the newest estimate
// propagated with the IMU to each reading that arrives after it (METHOD.md
// §4's prediction, one reading at a time). When a newer estimate arrives, the
// readings since its time are integrated again from it.
#include <cstdint>
#include <optional>
#include <vector>

#include "edgevio/imu/preintegration.h"

namespace edgevio::imu {

class ImuRatePropagator {
 public:
  /// `max_gap_s`: readings further apart than this are not integrated across
  /// (as in the window: estimator.max_imu_gap_s).
  explicit ImuRatePropagator(double max_gap_s);

  /// A newer estimate, of the body at t_ns; an older one than the current is ignored.
  void setEstimate(std::int64_t t_ns, const NavState& x);

  /// Takes the next reading (in time order) and returns the state at its time
  /// propagated from the newest estimate: nullopt before the first estimate,
  /// for a reading not after it, or across a gap.
  std::optional<NavState> propagate(const ImuSample& reading);

  /// The time of the estimate the last propagation started from; -1 before one.
  std::int64_t estimateTime() const { return t_estimate_; }
  /// Readings kept for a later estimate to start from (at most kKeptSeconds + 1 s worth).
  std::size_t keptReadings() const { return recent_.size(); }

  /// How far behind the newest reading an estimate may still arrive and take
  /// over [s]: a frame's pose that late is of no use to a controller, and
  /// the readings kept for it stay bounded when no estimate comes (a stalled
  /// tracker), 2,200 at 200 Hz.
  static constexpr double kKeptSeconds = 10.0;

 private:
  void integrateSince(std::int64_t t0_ns);

  double max_gap_s_;
  std::int64_t t_estimate_ = -1;
  NavState estimate_;
  Preintegration pre_;
  std::int64_t t_integrated_ = -1;  ///< pre_ covers [t_estimate_, t_integrated_]
  bool broken_ = false;             ///< a gap since the estimate: nothing until the next one
  std::vector<ImuSample> recent_;   ///< the readings since the estimate, and the one before
};

}  // namespace edgevio::imu
