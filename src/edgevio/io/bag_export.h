#pragma once
// Any sequence edgevio reads, written as a ROS 1 bag in EuRoC's layout:
// /cam0/image_raw and /cam1/image_raw (one message per stereo frame, both
// stamped with the left image's time), /imu0 and, when the sequence has
// ground truth, /groundtruth (geometry_msgs/PoseStamped, the body in the
// world); messages in time order, IMU and ground truth up to each frame
// before it. Kalibr's camchain-imucam.yaml and imu.yaml, naming those
// topics, are written beside the bag, so `edgevio run OUT.bag` finds them.
#include <functional>
#include <string>

#include "edgevio/common/options.h"
#include "edgevio/io/rosbag_writer.h"
#include "edgevio/io/sequence.h"

namespace edgevio::io {

enum class BagImages { kRaw, kPng };
inline constexpr options::Choice<BagImages> kBagImagesChoices[] = {
    {BagImages::kRaw, "raw", "sensor_msgs/Image, mono8"},
    {BagImages::kPng, "png", "sensor_msgs/CompressedImage, PNG"}};

struct BagExportOptions {
  BagCompression compression = BagCompression::kNone;
  BagImages images = BagImages::kRaw;
};

/// What was written.
struct BagExport {
  std::size_t stereo_frames = 0, imu_messages = 0, groundtruth_messages = 0;
  BagTopics topics;
  std::string camchain_yaml, imu_yaml;
};

/// Writes `seq` to `bag_path` (a .bag file; its folder is created), and
/// Kalibr's calibration beside it; `progress(frames written, frames)` after
/// each frame. Throws InputError naming the file that could not be written.
BagExport exportBag(Sequence& seq, const std::string& bag_path, const BagExportOptions& options,
                    const std::function<void(std::size_t, std::size_t)>& progress = {});

}  // namespace edgevio::io
