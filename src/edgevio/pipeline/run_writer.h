#pragma once
// The files of a run folder, written frame by frame as the run goes (memory
// does not grow with the sequence):
//   trajectory_tum.txt, trajectory.csv  the causal body pose of every processed frame
//                                       (trajectory.csv with velocity and biases in the IMU modes)
//   trajectory_imu_rate_tum.txt         IMU modes: the pose at every IMU reading (pipeline/imu_rate_output.h)
//   frames.csv                          one FrameRecord per row (columns: frameColumns())
//   summary.json                        the run as a whole (RunSummary)
//   config.yaml                         the configuration that ran
//   alignment/<t_ns>.jpg                the alignment pictures (tracking/alignment_picture.h) of
//                                       keyframes, of frames that failed, were rejected, restarted
//                                       the window or began a loss, and of every Nth frame
#include <fstream>
#include <iosfwd>
#include <string>
#include <vector>

#include "edgevio/config/config.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/pipeline/frame_record.h"
#include "edgevio/pipeline/run_summary.h"

namespace edgevio::pipeline {

/// Whether frame number `index` (from 0) keeps its alignment picture: every
/// frame something happened to, and every `stride`-th of the rest (0: none).
bool keepsPicture(const FrameRecord& record, std::size_t index, int stride);

class RunWriter {
 public:
  /// Creates the folder and writes config.yaml. Throws InputError when it cannot write there.
  RunWriter(const std::string& out_dir, const Config& config, bool with_velocity_and_bias);
  void write(const FrameRecord& record);
  /// Writes alignment/<t_ns>.jpg.
  void writePicture(std::int64_t t_ns, const std::vector<std::uint8_t>& jpeg);
  std::size_t poses() const { return tum_.count(); }
  /// Writes summary.json.
  void finish(const RunSummary& summary);

 private:
  std::string out_dir_;
  std::ofstream frames_csv_;
  io::TrajectoryWriter tum_, euroc_;
  bool pictures_folder_made_ = false;
};

/// The reference of a run folder's files as Markdown (docs/outputs.md): every
/// column of frames.csv and key of summary.json, from their tables.
void writeOutputsReference(std::ostream& out);

}  // namespace edgevio::pipeline
