#pragma once
// A ROS 1 bag as a sequence (io/sequence.h), read message by message.
//
// Topics: two image topics (sensor_msgs/Image or CompressedImage) and one
// IMU topic (sensor_msgs/Imu), given or found by their types; the left one
// is the topic Kalibr's calibration names for cam0, else the one whose name
// says cam0, left or infra1. Ground truth, optional: a PoseStamped,
// TransformStamped or Odometry topic, given (it is not guessed).
// Calibration: `--calib` (anything io/calibration_io.h reads), else Kalibr's
// camchain-imucam.yaml (with imu.yaml) or an ASL mav0/ folder beside the bag.
// Times are the messages' header stamps; stereo pairs are formed as for an
// ASL folder. Opening reads the index and every IMU message (and the ground
// truth), not the images.
//
// Bad input: a missing or ambiguous topic, a missing calibration, an image
// encoding edgevio does not read, an image whose size is not the
// calibration's, a message that does not parse: InputError naming the bag,
// the topic and the message's index. A damaged bag: see io/rosbag.h.
#include <memory>
#include <mutex>

#include "edgevio/io/rosbag.h"
#include "edgevio/io/sequence.h"

namespace edgevio::io {

class BagSequence final : public Sequence {
 public:
  BagSequence(const SequenceSource& source, const DatasetOptions& options);

  std::string name() const override;
  std::string location() const override;
  std::size_t frameCount() const override { return pairs_.size(); }
  std::int64_t frameTime(std::size_t i) const override { return left_.at(pairs_.at(i).first).stamp_ns; }
  std::optional<cv::Mat> leftImage(std::size_t i) override;
  std::function<cv::Mat()> rightImageLoader(std::size_t i) const override;
  std::size_t unreadableImages() const override { return out_of_order_[0] + out_of_order_[1]; }
  std::size_t cameraFrames(int cam) const override { return (cam == 0 ? left_ : right_).size(); }

  /// The topics it reads (cam0, cam1, imu, ground truth or "").
  const BagTopics& topics() const { return topics_; }

 private:
  /// One image message: where it is, its stamp, its index on the topic (for messages).
  struct ImageRef {
    BagMessageRef ref;
    std::int64_t stamp_ns = 0;
    std::size_t index = 0;
  };
  /// The ids of the connections on `topic`, which must be of one of `types`.
  std::vector<std::uint32_t> connectionsOf(const std::string& topic, const std::vector<std::string>& types, const char* what) const;
  void chooseTopics(const BagTopics& given);
  /// One pass over the bag in file order: the images' stamps, the IMU and the ground truth.
  void readMessages(const DatasetOptions& options);
  void checkImu(const DatasetOptions& options);
  /// The image, decoded and checked against camera `cam`'s size.
  cv::Mat decode(int cam, const ImageRef& image) const;

  std::string path_;
  mutable std::mutex mutex_;  ///< the reader: the driver and the tracking thread both read images
  std::unique_ptr<RosbagReader> reader_;
  BagTopics topics_;
  std::vector<std::uint32_t> image_connections_[2], imu_connections_, groundtruth_connections_;
  std::vector<ImageRef> left_, right_;
  std::vector<std::pair<std::size_t, std::size_t>> pairs_;
  std::size_t out_of_order_[2] = {0, 0};  ///< images skipped for a repeated or decreasing stamp
};

/// A bag's pose topic (PoseStamped, TransformStamped or Odometry; empty
/// `topic`: its only one) as a trajectory, in stamp order.
Trajectory readBagTrajectory(const std::string& bag, const std::string& topic = "");
/// A bag's IMU topic (empty `topic`: its only one), in stamp order.
std::vector<imu::ImuSample> readBagImu(const std::string& bag, const std::string& topic = "");

}  // namespace edgevio::io
