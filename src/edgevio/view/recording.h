#pragma once
// `edgevio run --mcap FILE`: the run as an MCAP recording that Foxglove and
// Lichtblick open directly (view/mcap_writer.h), written frame by frame as
// the run goes. JSON-encoded messages of Foxglove's schemas:
//   /tf                  foxglove.FrameTransforms  world → body → cam0, cam1 (every frame)
//   /pose                foxglove.PoseInFrame      the body's pose (every frame)
//   /path/estimate       foxglove.PosesInFrame     the estimate so far (each second of sensor time and at the end;
//                                                  at most kMaxPathPoses, evenly thinned)
//   /path/ground_truth   foxglove.PosesInFrame     the ground truth so far, placed at the estimate's first pose (with the estimate's)
//   /keyframes           foxglove.PosesInFrame     every keyframe's pose so far (each time one is made)
//   /alignment           foxglove.CompressedImage  the alignment picture (the frames that keep one)
//   /events              foxglove.Log              keyframes, failed and rejected alignments, restarts, losses, events
//   /frame               edgevio.FrameRecord       the frames.csv row as an object (every frame)
// Times are the frames' sensor timestamps.
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "edgevio/io/sequence.h"
#include "edgevio/pipeline/frame_record.h"
#include "edgevio/view/mcap_writer.h"

namespace edgevio::view {

class Recording {
 public:
  /// A path message holds at most this many poses (~300 KB of JSON): a
  /// 20 Hz run's path stays whole for 100 s. Paths are sent once per second
  /// of sensor time: each message repeats the whole path, so sending one
  /// per frame cost a quarter of the run's time on the demo.
  static constexpr std::size_t kMaxPathPoses = 2000;
  static constexpr std::int64_t kPathPeriodNs = 1000000000;

  /// Opens the file (InputError when it cannot) with the sequence's camera
  /// extrinsics and ground truth.
  Recording(const std::string& path, const io::Sequence& sequence);
  void write(const pipeline::FrameRecord& record, const std::vector<std::uint8_t>& jpeg);
  /// Sends the paths as they end and finishes the file (the destructor
  /// finishes it when this was not called).
  void close();

 private:
  void log(std::int64_t t_ns, int level, const std::string& message);
  void writePaths(std::int64_t t_ns);

  McapWriter mcap_;
  geometry::SE3 T_b_c_[2];
  io::Trajectory truth_;
  std::uint16_t tf_, pose_, path_, truth_path_ = 0, keyframes_, alignment_, events_, frame_;
  std::vector<geometry::SE3> estimate_, truth_so_far_, keyframe_poses_;
  bool truth_placed_ = false;
  std::int64_t last_t_ns_ = -1, paths_sent_ns_ = -1;  ///< the newest frame's time; when paths were last sent
  geometry::SE3 T_est_gt_;  ///< places the ground truth at the estimate's first pose
};

}  // namespace edgevio::view
