#include "edgevio/pipeline/run.h"

#include <sys/resource.h>

#include <chrono>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/common/error.h"
#include "edgevio/common/time.h"
#include "edgevio/imu/gyro_integration.h"
#include "edgevio/io/sequence.h"
#include "edgevio/pipeline/imu_rate_output.h"
#include "edgevio/pipeline/odometry.h"
#include "edgevio/pipeline/run_writer.h"
#include "edgevio/pipeline/threaded_pipeline.h"

namespace edgevio::pipeline {

namespace {

using Clock = std::chrono::steady_clock;
// Edges and points stay legible at this quality; a 376x240 picture is ~25 KB.
constexpr int kPictureJpegQuality = 80;

double peakResidentMb() {
  rusage usage{};
  return getrusage(RUSAGE_SELF, &usage) == 0 ? static_cast<double>(usage.ru_maxrss) / 1024.0 : 0.0;  // ru_maxrss is in KiB
}

void validate(const RunRequest& req, const Config& config) {
  if (req.skip < 0) throw InputError("--skip must be >= 0");
  if (req.skip_offset < 0 || req.skip_offset > req.skip)
    throw InputError("--skip-offset must be between 0 and --skip (" + std::to_string(req.skip) + ")");
  const std::string invalid = config.validate();
  if (!invalid.empty()) throw InputError("invalid configuration: " + invalid);
}

/// Every (skip+1)-th frame of the sequence from the offset-th on.
std::vector<std::size_t> framesToRun(const io::Sequence& sequence, int skip, int offset) {
  std::vector<std::size_t> frames;
  for (auto i = static_cast<std::size_t>(offset); i < sequence.frameCount(); i += static_cast<std::size_t>(skip) + 1) frames.push_back(i);
  return frames;
}

RunSummary startSummary(const RunRequest& req, const io::Sequence& sequence) {
  RunSummary s;
  s.mode = modeName(req.mode);
  s.sequence = sequence.name();
  s.dataset = sequence.location();
  s.skip = req.skip;
  s.skip_offset = req.skip_offset;
  s.realtime = req.realtime;
  s.duration_s = toSeconds(sequence.frameTime(sequence.frameCount() - 1) - sequence.frameTime(0));
  s.stereo_pairs = sequence.frameCount();
  return s;
}

/// Writes a frame's row (and its alignment picture when kept), counts it
/// into the summary and tells the observer of it and of its events.
void deliver(const FrameRecord& r, bool keep_picture, std::int64_t t0, RunWriter& writer, RunSummary& s,
             const RunObserver& observer) {
  writer.write(r);
  std::vector<std::uint8_t> jpeg;
  if (keep_picture) {
    jpeg = tracking::encodeJpeg(tracking::drawAlignmentPicture(*r.picture), kPictureJpegQuality);
    writer.writePicture(r.t_ns, jpeg);
  }
  const std::size_t events_before = s.events.size();
  s.count(r, t0);
  if (observer.event)
    for (std::size_t e = events_before; e < s.events.size(); ++e) observer.event(s.events[e]);
  if (observer.frame) observer.frame(r, jpeg);
}

}  // namespace

RunSummary run(const RunRequest& req, const Config& config, const RunObserver& observer) {
  const auto wall_start = Clock::now();
  validate(req, config);
  const std::unique_ptr<io::Sequence> sequence = io::openSequence({req.dataset, req.calib, req.topics}, config.dataset);
  if (sequence->frameCount() == 0) throw InputError(req.dataset, 0, "no stereo pairs to process");
  const std::vector<std::size_t> frames = framesToRun(*sequence, req.skip, req.skip_offset);
  if (frames.empty())
    throw InputError(req.dataset, 0, "--skip-offset " + std::to_string(req.skip_offset) + " is past its " +
                                         std::to_string(sequence->frameCount()) + " stereo pair(s): use a smaller offset");
  const camera::StereoRectifier rect(sequence->calibration(), config.rectification);
  RunWriter writer(req.out_dir, config, req.mode.imu);
  RunSummary s = startSummary(req, *sequence);
  if (observer.opened) observer.opened(*sequence);

  // Static start: gravity-aligned initial orientation and gyro bias (METHOD.md §5).
  const std::int64_t t0 = sequence->frameTime(frames.front());
  const tracking::TrackingOptions& to = config.tracking;
  const imu::StaticInit init = imu::staticInitialization(sequence->imu(), t0, to.static_init_window_s, to.static_chunk_s,
                                                         to.static_accel_std_max, to.static_gyro_std_max);
  s.static_initialization = init.is_static;
  const std::unique_ptr<tracking::Tracker> tracker =
      req.tracker ? req.tracker(rect, config)
                  : std::make_unique<tracking::EdgeTracker>(rect, config.vision, config.alignment, config.tracking);
  if (!tracker) throw InputError("the run request's tracker factory returned no tracker");
  Odometry odometry(req.mode, config, *tracker, rect.T_b_rect(0), sequence->calibration().imu, sequence->imu(), init, req.realtime,
                    req.picture_stride > 0);

  s.frames_to_process = frames.size();
  std::optional<ImuRateOutput> imu_rate;
  if (req.mode.imu)
    imu_rate.emplace(sequence->imu(), config.estimator.max_imu_gap_s,
                     req.out_dir + "/trajectory_imu_rate_tum.txt", req.realtime, t0,
                     Clock::now());
  std::size_t done = 0;
  const PipelineResult p = runThreaded(*sequence, frames, rect, config.vision, req.realtime, [&](PipelineFrame item) {
    ++done;
    if (!item.readable) {
      ++s.unreadable_frames;
      return;
    }
    const auto t_start = Clock::now();
    double latency_ms = 0.0;
    FrameRecord r = odometry.process(std::move(item.frame), [&](const FrameRecord& posed) {
      latency_ms = std::chrono::duration<double, std::milli>(Clock::now() - item.released).count();
      if (imu_rate && posed.state)
        imu_rate->publish(posed.t_ns, *posed.state, posed.calibration ? toNanoseconds(posed.calibration->time_offset_s) : 0);
    });
    r.total_ms = item.load_ms + std::chrono::duration<double, std::milli>(Clock::now() - t_start).count();
    r.latency_ms = latency_ms;
    deliver(r, keepsPicture(r, done - 1, req.picture_stride), t0, writer, s, observer);
    if (observer.progress) observer.progress(done + item.dropped_before, frames.size(), toSeconds(r.t_ns - t0));
  });
  if (writer.poses() == 0) throw InputError(req.dataset, 0, "no stereo pair could be read");
  if (imu_rate) {
    s.imu_rate_latencies_ms = imu_rate->finish(sequence->frameTime(frames.back()));
    s.imu_rate_poses = imu_rate->poses();
    s.imu_rate_realtime_priority = imu_rate->realtimePriority();
  }

  s.finish();
  s.dropped_frames = p.dropped;
  s.skipped_unreadable = sequence->unreadableImages();
  s.warnings = sequence->warnings();
  s.wall_s = std::chrono::duration<double>(Clock::now() - wall_start).count();
  s.realtime_factor = s.wall_s > 0 ? s.duration_s / s.wall_s : 0.0;
  s.peak_rss_mb = peakResidentMb();
  writer.finish(s);
  return s;
}

}  // namespace edgevio::pipeline
