#pragma once
// Whether the estimate can still be trusted, decided frame by frame from
// what the frame's record says. A loss is an interval, not the run's
// verdict: it begins at its first symptom and ends at the first frame
// tracked again.
//
// Signals:
//  - a run of tracking.lost_after_failures consecutive self-check failures
//    (METHOD.md §3: the frames are dead-reckoned, and after that many the
//    motion since the last good frame is beyond what the alignment's basin
//    recovers);
//  - tracking.lost_gyro_contradictions of the last lost_after_failures
//    aligned frames rotating more than tracking.lost_gyro_disagreement_deg
//    away from the gyroscope: frozen or occluded images and a visual estimate
//    drifting away pass the self check, but the gyroscope does not agree.
//    A self-check failure counts as such evidence too where the IMU did not
//    carry the frame (the visual modes, an IMU gap, before the window's
//    first IMU reading: a frame without a window state), since its pose is
//    then a guess; a frame the IMU carried is not. Such a loss ends at a
//    tracked frame once fewer remain in that window;
//  - a frozen image (the previous frame's to the last pixel): where the IMU
//    did not carry the frame its pose is a guess at once, until a new image
//    tracks; where it did, it counts as a self-check failure;
//  - a pose whose step implies an acceleration beyond tracking.lost_accel_mps2
//    or a speed beyond tracking.lost_speed_mps (the alignment went to another
//    basin, or the estimate exploded or runs away), or that lies further from
//    the accelerometer's prediction than tracking.lost_accel_disagreement_m
//    plus lost_accel_disagreement_mps2's reach (a smaller jump the other
//    checks pass); such a loss ends at a tracked frame with a plausible step
//    again;
//  - a non-finite pose.
#include <cstdint>
#include <deque>

#include "edgevio/pipeline/frame_record.h"
#include "edgevio/tracking/tracking_options.h"

namespace edgevio::pipeline {

class LossMonitor {
 public:
  /// The tracking.lost_* options; lost_gyro_contradictions or
  /// lost_gyro_disagreement_deg 0: no gyroscope signal; lost_accel_mps2, lost_speed_mps or lost_accel_disagreement_m 0: no such signal.
  explicit LossMonitor(const tracking::TrackingOptions& o)
      : lost_after_(o.lost_after_failures),
        gyro_disagreement_deg_(o.lost_gyro_disagreement_deg),
        gyro_contradictions_(o.lost_gyro_contradictions),
        accel_mps2_(o.lost_accel_mps2),
        speed_mps_(o.lost_speed_mps),
        disagreement_m_(o.lost_accel_disagreement_m),
        disagreement_mps2_(o.lost_accel_disagreement_mps2) {}

  /// Sets r->status, and r->lost_since_ns and r->lost_reason where a loss begins.
  void update(FrameRecord* r);
  /// Whether the last frame updated was lost.
  bool lost() const { return lost_ != Cause::kNone; }

 private:
  enum class Cause { kNone, kFailures, kEvidence, kImplausibleMotion };
  struct Recent {
    std::int64_t t_ns;
    bool contradicted, guessed;  ///< the gyroscope contradicted it; it failed and the IMU did not carry it
  };

  /// The accelerometer disagreement a frame at t_ns may have; moves the frame times on.
  double disagreementBound(std::int64_t t_ns);

  int lost_after_;
  double gyro_disagreement_deg_;
  int gyro_contradictions_;
  double accel_mps2_, speed_mps_, disagreement_m_, disagreement_mps2_;
  std::int64_t t_prev_ns_ = -1, t_before_ns_ = -1;  ///< the previous two frames' times
  int failures_ = 0;  ///< consecutive self-check failures
  std::int64_t first_failure_ns_ = -1;
  /// The last lost_after_ aligned frames: their times, whether the gyroscope contradicted them and whether their pose is a guess.
  std::deque<Recent> recent_;
  Cause lost_ = Cause::kNone;
};

}  // namespace edgevio::pipeline
