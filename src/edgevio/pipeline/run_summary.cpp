#include "edgevio/pipeline/run_summary.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "edgevio/common/format.h"
#include "edgevio/common/json.h"
#include "edgevio/common/time.h"

namespace edgevio::pipeline {

void RunSummary::count(const FrameRecord& r, std::int64_t t0_ns) {
  ++frames;
  keyframes += static_cast<std::size_t>(r.keyframes_made);
  const bool failed_check = r.aligned && !r.selfCheckPassed();
  self_check_failures += failed_check;
  gyro_check_realignments += r.gyro_check_failed;
  translation_check_realignments += r.translation_check_failed;
  motion_check_realignments += r.motion_check_failed;
  external_check_rejections += r.external_check == ExternalCheck::kRejected;
  estimator_resets += r.restart != WindowRestart::kNone;
  loop_closures += static_cast<std::size_t>(r.loop_links);
  back_links += static_cast<std::size_t>(r.back_links);
  latencies_ms.push_back(r.latency_ms);
  if (r.calibration) calibration = r.calibration;
  const double t = toSeconds(r.t_ns - t0_ns);
  const auto event = [&](const std::string& what) { events.push_back(formatText("t = %.3f s: ", t) + what); };
  for (const std::string& e : r.events) event(e);
  const bool lost = r.status == TrackingStatus::kLost;
  if (lost && r.lost_since_ns >= 0) {
    lost_intervals.push_back({toSeconds(r.lost_since_ns - t0_ns), t, r.lost_reason, true});
    event("estimate lost (" + r.lost_reason + ")");
  }
  if (!lost_intervals.empty() && lost_intervals.back().open) {
    LostInterval& l = lost_intervals.back();
    l.end_s = t;
    l.open = lost;
    if (!lost) event(formatText("tracking again after %.2f s lost", l.end_s - l.start_s));
  }
  trusted_frames += !lost;
}

void RunSummary::finish() {
  if (frames == 0) {
    failed = true;
    failure = "no frame was processed";
  } else if (trusted_frames == 0) {
    failed = true;
    failure = "no frame was tracked";
  }
}

double RunSummary::lostSeconds() const {
  double s = 0.0;
  for (const LostInterval& l : lost_intervals) s += l.end_s - l.start_s;
  return s;
}

long long RunSummary::unaccountedFrames() const {
  return static_cast<long long>(frames_to_process) - static_cast<long long>(frames + dropped_frames + unreadable_frames);
}

std::string RunSummary::lossText() const {
  if (lost_intervals.empty()) return "";
  return formatText("lost %.2f s in %zu interval(s) (summary.json lost_intervals)", lostSeconds(), lost_intervals.size());
}

double nearestRankPercentile(std::vector<double> values, double p) {
  if (values.empty()) return 0.0;
  std::sort(values.begin(), values.end());
  const auto rank = static_cast<std::size_t>(std::ceil(p / 100.0 * static_cast<double>(values.size())));
  return values[std::clamp<std::size_t>(rank, 1, values.size()) - 1];
}

namespace {
void strings(JsonWriter& j, const std::vector<std::string>& v) {
  j.beginArray();
  for (const std::string& x : v) j.value(x);
  j.endArray();
}
/// Writes one member of the summary as a JSON value.
template <auto M>
void member(JsonWriter& j, const RunSummary& s) {
  j.value(s.*M);
}
/// {p50, p99, max} of latencies [ms].
void onlineCalibration(JsonWriter& j, const std::optional<estimator::CalibrationState>& c) {
  if (!c) {
    j.null();
    return;
  }
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  j.beginObject();
  j.key("time_offset_ms").value(c->time_offset ? 1e3 * c->time_offset_s : kNaN);
  j.key("cam_imu_rotation_correction_deg");
  if (c->rotation) {
    const Vec3 v = c->R_correction.log() * kRadToDeg;
    j.beginArray().value(v.x()).value(v.y()).value(v.z()).endArray();
  } else {
    j.null();
  }
  j.key("cam_imu_rotation_correction_angle_deg").value(c->rotation ? geometry::angle(c->R_correction) * kRadToDeg : kNaN);
  j.key("cam_imu_translation_correction_m");
  if (c->translation)
    j.beginArray().value(c->t_correction.x()).value(c->t_correction.y()).value(c->t_correction.z()).endArray();
  else
    j.null();
  j.endObject();
}

void percentiles(JsonWriter& j, const std::vector<double>& latencies_ms) {
  j.beginObject();
  j.key("p50").value(nearestRankPercentile(latencies_ms, 50)).key("p99").value(nearestRankPercentile(latencies_ms, 99));
  j.key("max").value(nearestRankPercentile(latencies_ms, 100));
  j.endObject();
}
}  // namespace

const std::vector<SummaryField>& summaryFields() {
  using S = RunSummary;
  using J = JsonWriter;
  static const std::vector<SummaryField> fields = {
      {"mode", "edge-only | edge+loop | edge+imu | edge+imu+loop", member<&S::mode>},
      {"sequence", "the sequence's name (its folder's)", member<&S::sequence>},
      {"dataset", "where it was read from (absolute; `edgevio eval --results` finds the ground truth there)",
       member<&S::dataset>},
      {"skip", "frames skipped between processed ones (--skip)", member<&S::skip>},
      {"skip_offset", "the first frame processed, 0..skip (--skip-offset)", member<&S::skip_offset>},
      {"frames", "frames processed (rows of frames.csv)", member<&S::frames>},
      {"keyframes", "keyframes made", member<&S::keyframes>},
      {"self_check_failures", "alignments that failed their self check", member<&S::self_check_failures>},
      {"gyro_check_realignments", "alignments redone because their rotation was far from the gyroscope's",
       member<&S::gyro_check_realignments>},
      {"translation_check_realignments", "alignments redone because their translation was far from the IMU's",
       member<&S::translation_check_realignments>},
      {"motion_check_realignments",
       "alignments redone because, without the IMU, they lay beyond the constant-velocity prediction's reach",
       member<&S::motion_check_realignments>},
      {"external_check_rejections", "tracking links the external check refused", member<&S::external_check_rejections>},
      {"estimator_resets", "restarts of the window (IMU gaps, estimates that blew up)", member<&S::estimator_resets>},
      {"loop_closures", "loop links that entered the window", member<&S::loop_closures>},
      {"back_links", "back links that entered the window", member<&S::back_links>},
      {"skipped_unreadable_frames", "images that were missing, did not decode, or were out of time order", member<&S::skipped_unreadable>},
      {"realtime", "true: frames were released at their timestamps (--realtime)", member<&S::realtime>},
      {"dropped_frames", "real time: frames dropped because the pipeline was behind", member<&S::dropped_frames>},
      {"stereo_pairs", "the sequence's stereo pairs (left and right image of one time)", member<&S::stereo_pairs>},
      {"frames_to_process", "the stereo pairs --skip keeps", member<&S::frames_to_process>},
      {"unreadable_frames", "frames to process whose left image did not decode: no row", member<&S::unreadable_frames>},
      {"unaccounted_frames",
       "frames_to_process - frames - dropped_frames - unreadable_frames: frames lost without a word (negative: rows without a frame), 0 in a sound run",
       [](J& j, const S& s) { j.value(s.unaccountedFrames()); }},
      {"static_initialization", "true: the IMU was still at the start, and gave gravity and the gyroscope bias",
       member<&S::static_initialization>},
      {"failed", "true: the run produced no estimate (no frame processed, or none tracked); losses on the way are lost_intervals",
       member<&S::failed>},
      {"failure", "why", member<&S::failure>},
      {"lost_intervals",
       "where the estimate was not trusted (frames.csv status lost), each {start_s, end_s, reason}: seconds after the first "
       "frame from the loss's first symptom to the first frame tracked again (or the last frame)",
       [](J& j, const S& s) {
         j.beginArray();
         for (const LostInterval& l : s.lost_intervals) {
           j.beginObject();
           j.key("start_s").value(l.start_s).key("end_s").value(l.end_s).key("reason").value(l.reason);
           j.endObject();
         }
         j.endArray();
       }},
      {"duration_s", "the sequence's length [s]", member<&S::duration_s>},
      {"wall_s", "the run's wall time [s]", member<&S::wall_s>},
      {"realtime_factor", "duration_s / wall_s", member<&S::realtime_factor>},
      {"peak_rss_mb", "peak resident memory of the process [MB]", member<&S::peak_rss_mb>},
      {"latency_ms", "frames.csv's latency_ms over the run: {p50, p99, max} (nearest-rank percentiles) [ms]",
       [](J& j, const S& s) { percentiles(j, s.latencies_ms); }},
      {"imu_rate_poses",
       "IMU modes: poses in trajectory_imu_rate_tum.txt, one per IMU reading after the first estimate up to the last frame "
       "(fewer across IMU gaps; in real time, from the first frame's release until the last frame's pose)",
       member<&S::imu_rate_poses>},
      {"imu_rate_latency_ms",
       "real time, IMU modes: from each IMU reading's release (at its timestamp, as frames are released) to its "
       "IMU-rate pose: {p50, p99, max} [ms]; 0 offline",
       [](J& j, const S& s) { percentiles(j, s.imu_rate_latencies_ms); }},
      {"imu_rate_realtime_priority",
       "real time, IMU modes: the IMU-rate thread ran at real-time scheduling priority (SCHED_FIFO: root, CAP_SYS_NICE or "
       "an rtprio limit); without it a reading can wait for a core behind the frame threads",
       member<&S::imu_rate_realtime_priority>},
      {"online_calibration",
       "the window's last camera-IMU calibration estimate (estimator.estimate_time_offset, estimate_cam_imu_rotation, "
       "estimate_cam_imu_translation), or null: {time_offset_ms (IMU time minus camera time), "
       "cam_imu_rotation_correction_deg (the rotation vector of R in T_b_c = T_b_c(calibration) (R, t)), "
       "cam_imu_rotation_correction_angle_deg, cam_imu_translation_correction_m (t)}; a part not estimated is null",
       [](J& j, const S& s) { onlineCalibration(j, s.calibration); }},
      {"events", "restarts, IMU gaps, unreadable images, each as \"t = … s: what\"", [](J& j, const S& s) { strings(j, s.events); }},
      {"warnings", "the dataset's warnings (missing images, IMU gaps, unpaired frames)",
       [](J& j, const S& s) { strings(j, s.warnings); }},
  };
  return fields;
}

void writeSummaryJson(std::ostream& out, const RunSummary& s) {
  JsonWriter j(out);
  j.beginObject();
  for (const SummaryField& f : summaryFields()) {
    j.key(f.key);
    f.write(j, s);
  }
  j.endObject();
}

}  // namespace edgevio::pipeline
