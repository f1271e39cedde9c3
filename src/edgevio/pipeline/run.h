#pragma once
// `edgevio run`: a sequence through the system, into a run folder
// (pipeline/run_writer.h). The sequence source, the thread pipeline
// (pipeline/threaded_pipeline.h), the per-frame stage code
// (pipeline/odometry.h) and the writers, put together.
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "edgevio/config/config.h"
#include "edgevio/io/sequence.h"
#include "edgevio/pipeline/frame_record.h"
#include "edgevio/pipeline/mode.h"
#include "edgevio/pipeline/run_summary.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::pipeline {

struct RunRequest {
  RunRequest() = default;
  RunRequest(std::string dataset_path, std::string out, Mode run_mode = {}, int skip_frames = 0)
      : dataset(std::move(dataset_path)), out_dir(std::move(out)), mode(run_mode), skip(skip_frames) {}

  std::string dataset;
  std::string out_dir;
  Mode mode;              ///< default: the full system
  int skip = 0;           ///< keep every (skip+1)-th stereo frame; the IMU is untouched
  int skip_offset = 0;    ///< the first frame kept, 0..skip: the skip+1 offsets together use every frame once
  bool realtime = false;  ///< release frames at their timestamps; drop those the pipeline has no room for
  std::string calib;      ///< a bag's calibration (empty: found beside it)
  io::BagTopics topics;   ///< a bag's topics (empty: found by type)
  int picture_stride = 10;  ///< keep the alignment picture of every Nth uneventful frame (run_writer.h); 0: no pictures
  /// The front end, for diagnostics that change what it sees (a tracker around
  /// the edge tracker, e.g. with a render's true keyframe depths:
  /// bench/link_consistency_bench); empty: the edge tracker.
  std::function<std::unique_ptr<tracking::Tracker>(const camera::StereoRectifier&, const Config&)> tracker;
};

/// What a caller may watch while a run goes.
struct RunObserver {
  /// The sequence, once opened (its calibration and ground truth), before any frame.
  std::function<void(const io::Sequence&)> opened;
  /// (frames done, frames total, sequence seconds done)
  std::function<void(std::size_t, std::size_t, double)> progress;
  /// Each event (window restart, IMU gap, unreadable image) as it happens, "t = … s: what".
  std::function<void(const std::string&)> event;
  /// Each frame's record, after it was written, with its alignment picture
  /// as JPEG bytes when the frame kept one (else empty).
  std::function<void(const FrameRecord&, const std::vector<std::uint8_t>&)> frame;
};

/// Throws InputError for bad input; a run that loses track returns failed = true.
RunSummary run(const RunRequest& request, const Config& config, const RunObserver& observer = {});

}  // namespace edgevio::pipeline
