#pragma once
// A recorded stereo + IMU sequence as the pipeline reads it: the calibration,
// the whole IMU log (small), and stereo frames one at a time, decoded when
// asked for and never held. An EuRoC/ASL folder is one (io/euroc_dataset.h).
#include <opencv2/core.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "edgevio/camera/calibration.h"
#include "edgevio/imu/imu_types.h"
#include "edgevio/io/dataset_options.h"
#include "edgevio/io/trajectory_io.h"

namespace edgevio::io {

class Sequence {
 public:
  virtual ~Sequence() = default;
  /// A short name (the folder's), for reports.
  virtual std::string name() const = 0;
  /// Where it was read from, as an absolute path.
  virtual std::string location() const = 0;
  const camera::StereoRig& calibration() const { return rig_; }
  const std::vector<imu::ImuSample>& imu() const { return imu_; }
  /// Ground truth, empty when the sequence has none.
  const Trajectory& groundTruth() const { return ground_truth_; }

  /// Stereo frames (pairs of left and right images), in time order.
  virtual std::size_t frameCount() const = 0;
  virtual std::int64_t frameTime(std::size_t i) const = 0;
  /// Frame i's left image, raw. nullopt (counted, with a warning) when it
  /// does not decode; InputError when its size is not the calibration's.
  virtual std::optional<cv::Mat> leftImage(std::size_t i) = 0;
  /// How to decode frame i's right image, raw, later and on any thread
  /// (only keyframes need it); the loader returns an empty image when it
  /// does not decode or its size is not the calibration's.
  virtual std::function<cv::Mat()> rightImageLoader(std::size_t i) const = 0;

  /// Warnings collected so far (opening and every image read).
  const std::vector<std::string>& warnings() const { return warnings_; }
  /// Images that were missing, did not decode, or were out of time order (so far).
  virtual std::size_t unreadableImages() const = 0;
  /// Readable images of camera `cam` (0 left, 1 right), paired or not.
  virtual std::size_t cameraFrames(int cam) const = 0;

 protected:
  // What every sequence has, filled by the reader when it opens.
  camera::StereoRig rig_;
  std::vector<imu::ImuSample> imu_;
  Trajectory ground_truth_;
  std::vector<std::string> warnings_;
};

/// The topics of a ROS bag to read (empty: found by their message types).
struct BagTopics {
  std::string cam0, cam1, imu, groundtruth;
};

/// Where a sequence is: an EuRoC/ASL folder (the folder holding mav0/, or
/// mav0 itself) or a ROS 1 bag, and, for a bag, its calibration (empty:
/// found beside it) and topics.
struct SequenceSource {
  std::string path;
  std::string calib;
  BagTopics topics;
};

/// Opens a sequence. Throws InputError naming what is wrong and what to pass.
std::unique_ptr<Sequence> openSequence(const SequenceSource& source, const DatasetOptions& options);

/// Replaces the IMU glitches of a sequence's log (imu/imu_glitches.h, the
/// thresholds of `options`), saying so in one warning naming `where`, and
/// moves its stamps onto the cameras' clock: back by the calibration's
/// offset (`rig`, Kalibr's timeshift_cam_imu) plus dataset.imu_time_offset_ms.
void prepareImuLog(std::vector<imu::ImuSample>* imu, const camera::StereoRig& rig, const DatasetOptions& options,
                   const std::string& where, std::vector<std::string>* warnings);

/// Pairs left and right image times (both increasing) that lie within
/// `tolerance_ns` of each other, in order: (left index, right index) per
/// pair. Adds the frames of each camera left without a partner to `unpaired`.
std::vector<std::pair<std::size_t, std::size_t>> pairStereo(const std::vector<std::int64_t>& left,
                                                            const std::vector<std::int64_t>& right, std::int64_t tolerance_ns,
                                                            std::size_t unpaired[2]);

}  // namespace edgevio::io
