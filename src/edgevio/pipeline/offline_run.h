#pragma once
// `edgevio run`: three threads (driver, pyramid, tracking + estimation)
// joined by bounded queues. Offline (default) the queues block, so the same
// input and config give the same trajectory, bit for bit; with `realtime`
// frames are released at their timestamps and dropped (counted) when the
// pipeline is behind. Writes to the output folder:
//   trajectory_tum.txt, trajectory.csv  the causal body pose of every processed frame
//   frames.csv                          per frame: keyframe, self check, points, iterations,
//                                       mean distance, the tracking link (reference time and
//                                       the body's motion T_bn_br), external check, estimator
//                                       iterations, cost, marginalised state, ms per component
//   summary.json                        mode, counts, failed, wall time, real-time factor
//   config.yaml                         the configuration used
#include <functional>
#include <string>
#include <vector>

#include "edgevio/config/config.h"

namespace edgevio::pipeline {

struct RunRequest {
  std::string dataset;
  std::string out_dir;
  std::string mode = "edge+imu+loop";
  int skip = 0;  ///< keep every (skip+1)-th stereo frame; the IMU is untouched
  bool realtime = false;  ///< release frames at their timestamps; drop those the pipeline has no room for
};

struct RunSummary {
  std::size_t frames = 0, keyframes = 0, self_check_failures = 0, skipped_unreadable = 0;
  std::size_t external_check_rejections = 0, estimator_resets = 0, loop_closures = 0;
  std::size_t back_links = 0;  ///< keyframe back links that entered the window
  std::size_t dropped_frames = 0;  ///< real-time mode: frames dropped because the pipeline was behind
  /// Alignments redone from the prediction: far from the gyroscope's rotation, or
  /// (IMU modes) from the IMU's translation (tracking.gyro_check_deg, imu_translation_check_m).
  std::size_t gyro_check_realignments = 0, translation_check_realignments = 0;
  std::vector<std::string> events;  ///< resets and IMU gaps, "t = … s: what"
  bool failed = false;
  std::string failure;
  double wall_s = 0.0, duration_s = 0.0, realtime_factor = 0.0;
  double peak_rss_mb = 0.0;  ///< peak resident memory of the process so far (getrusage)
};

/// (frames done, frames total, sequence seconds done)
using RunProgress = std::function<void(std::size_t, std::size_t, double)>;

/// Receives each event (estimator reset, IMU gap) as it happens.
using EventLog = std::function<void(const std::string&)>;

/// Throws InputError for bad input; a run that loses track returns failed = true.
RunSummary runOffline(const RunRequest& request, const Config& config, const RunProgress& progress = {},
                      const EventLog& event_log = {});

}  // namespace edgevio::pipeline
