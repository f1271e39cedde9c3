#pragma once
// What a run did as a whole (summary.json): counted from its frame records,
// one record at a time, in one place.
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "edgevio/common/json.h"
#include "edgevio/pipeline/frame_record.h"

namespace edgevio::pipeline {

/// Nearest-rank percentile `p` (0 < p <= 100): the smallest value with at
/// least p % of the values at or below it; 0 without values.
double nearestRankPercentile(std::vector<double> values, double p);

/// A time span where the estimate was not trusted (frames.csv status lost).
struct LostInterval {
  double start_s = 0.0, end_s = 0.0;  ///< after the first frame: its first symptom, and the first frame tracked again (or the last frame)
  std::string reason;
  bool open = true;  ///< not tracked again yet
};

struct RunSummary {
  std::string mode, sequence, dataset;
  int skip = 0, skip_offset = 0;
  bool realtime = false;
  bool static_initialization = false;
  std::size_t frames = 0, keyframes = 0, self_check_failures = 0;
  /// Alignments redone from the prediction: far from the gyroscope's rotation,
  /// (IMU modes) from the IMU's translation, or (without the IMU) beyond the
  /// motion model's reach (tracking.gyro_check_deg, imu_translation_check_m,
  /// constant_velocity_max_accel_mps2).
  std::size_t gyro_check_realignments = 0, translation_check_realignments = 0, motion_check_realignments = 0;
  std::size_t external_check_rejections = 0, estimator_resets = 0, loop_closures = 0;
  std::size_t back_links = 0;              ///< keyframe back links that entered the window
  std::size_t skipped_unreadable = 0;      ///< frames whose image did not decode or was missing
  std::size_t dropped_frames = 0;          ///< real-time mode: frames dropped because the pipeline was behind
  std::size_t stereo_pairs = 0;            ///< the sequence's stereo pairs
  std::size_t frames_to_process = 0;       ///< of those, the frames --skip keeps
  std::size_t unreadable_frames = 0;       ///< frames to process whose left image did not decode (no row)
  std::vector<std::string> events;         ///< restarts, IMU gaps, unreadable images: "t = … s: what"
  std::vector<std::string> warnings;       ///< the dataset's
  std::vector<LostInterval> lost_intervals;
  bool failed = false;  ///< no estimate: no frame processed, or none trusted
  std::string failure;
  double wall_s = 0.0, duration_s = 0.0, realtime_factor = 0.0;
  double peak_rss_mb = 0.0;  ///< peak resident memory of the process so far (getrusage)
  std::vector<double> latencies_ms;  ///< every frame's latency_ms, in order
  std::size_t imu_rate_poses = 0;            ///< IMU modes: poses in trajectory_imu_rate_tum.txt
  std::vector<double> imu_rate_latencies_ms;  ///< real time: each of those poses' latency, in order
  bool imu_rate_realtime_priority = false;    ///< real time: the IMU-rate thread ran at real-time priority
  std::size_t trusted_frames = 0;    ///< frames with status ok
  /// The last frame's camera-IMU calibration estimate, when the window estimated one.
  std::optional<estimator::CalibrationState> calibration;

  /// The total length of the lost intervals [s].
  double lostSeconds() const;
  /// Frames to process that neither have a row nor were dropped or unreadable
  /// (negative: more rows than frames): 0 unless the pipeline lost or invented frames.
  long long unaccountedFrames() const;
  /// "lost 1.20 s in 2 interval(s) (…)", or "" when nothing was lost.
  std::string lossText() const;
  /// Nearest-rank percentile `p` (0 < p <= 100) of the frames' latencies; 0 without frames.
  double latencyPercentile(double p) const { return nearestRankPercentile(latencies_ms, p); }

  /// Counts one frame. `t0_ns`: the sequence's first frame, for event and loss times.
  void count(const FrameRecord& r, std::int64_t t0_ns);
  /// After the last frame: whether the run produced an estimate at all.
  void finish();
};

/// One key of summary.json: its name, meaning, and how to write its value.
struct SummaryField {
  const char* key;
  const char* meaning;
  void (*write)(JsonWriter&, const RunSummary&);
};

/// The keys of summary.json, in order.
const std::vector<SummaryField>& summaryFields();

/// summary.json.
void writeSummaryJson(std::ostream& out, const RunSummary& s);

}  // namespace edgevio::pipeline
