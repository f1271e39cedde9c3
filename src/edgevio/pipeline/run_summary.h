#pragma once
// What a run did as a whole (summary.json): counted from its frame records,
// one record at a time, in one place.
#include <cstddef>
#include <string>
#include <vector>

#include "edgevio/common/json.h"
#include "edgevio/pipeline/frame_record.h"

namespace edgevio::pipeline {

struct RunSummary {
  std::string mode, sequence, dataset;
  int skip = 0;
  bool realtime = false;
  bool static_initialization = false;
  std::size_t frames = 0, keyframes = 0, self_check_failures = 0;
  /// Alignments redone from the prediction: far from the gyroscope's rotation, or
  /// (IMU modes) from the IMU's translation (tracking.gyro_check_deg, imu_translation_check_m).
  std::size_t gyro_check_realignments = 0, translation_check_realignments = 0;
  std::size_t external_check_rejections = 0, estimator_resets = 0, loop_closures = 0;
  std::size_t back_links = 0;              ///< keyframe back links that entered the window
  std::size_t skipped_unreadable = 0;      ///< frames whose image did not decode or was missing
  std::size_t dropped_frames = 0;          ///< real-time mode: frames dropped because the pipeline was behind
  std::vector<std::string> events;         ///< restarts, IMU gaps, unreadable images: "t = … s: what"
  std::vector<std::string> warnings;       ///< the dataset's
  bool failed = false;
  std::string failure;
  double wall_s = 0.0, duration_s = 0.0, realtime_factor = 0.0;
  double peak_rss_mb = 0.0;  ///< peak resident memory of the process so far (getrusage)
  int consecutive_failures = 0;  ///< self-check failures in a row so far
  std::vector<double> latencies_ms;  ///< every frame's latency_ms, in order

  /// Nearest-rank percentile `p` (0 < p <= 100) of the frames' latencies; 0 without frames.
  double latencyPercentile(double p) const;

  /// Counts one frame. `t0_ns`: the sequence's first frame, for event times;
  /// `lost_after`: consecutive self-check failures that make the run lost.
  void count(const FrameRecord& r, std::int64_t t0_ns, int lost_after);
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
