#include "edgevio/io/bag_export.h"

#include <filesystem>

#include "edgevio/common/error.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/io/ros_messages.h"

namespace edgevio::io {

namespace fs = std::filesystem;

BagExport exportBag(Sequence& seq, const std::string& bag_path, const BagExportOptions& options,
                    const std::function<void(std::size_t, std::size_t)>& progress) {
  if (fs::path(bag_path).extension() != ".bag") throw InputError(bag_path, 0, "the output must be a .bag file");
  const fs::path dir = fs::absolute(bag_path).parent_path();
  fs::create_directories(dir);
  BagExport result;
  result.topics = {"/cam0/image_raw", "/cam1/image_raw", "/imu0", seq.groundTruth().empty() ? "" : "/groundtruth"};
  const bool png = options.images == BagImages::kPng;
  RosbagWriter bag(bag_path, options.compression);
  const std::string image_type = png ? ros::kCompressedImage : ros::kImage;
  const std::uint32_t cam[2] = {bag.addConnection(result.topics.cam0, image_type), bag.addConnection(result.topics.cam1, image_type)};
  const std::uint32_t imu = bag.addConnection(result.topics.imu, ros::kImu);
  const std::uint32_t gt = result.topics.groundtruth.empty() ? 0 : bag.addConnection(result.topics.groundtruth, ros::kPoseStamped);
  const auto image = [&](std::int64_t t, const cv::Mat& m, const char* frame) {
    return png ? ros::serializeCompressedPng(t, frame, m) : ros::serializeImage(t, frame, m);
  };
  const std::vector<imu::ImuSample>& imu_log = seq.imu();
  const Trajectory& truth = seq.groundTruth();
  const auto writeUntil = [&](std::int64_t t) {  // IMU and ground truth up to time t
    for (; result.imu_messages < imu_log.size() && imu_log[result.imu_messages].t_ns <= t; ++result.imu_messages)
      bag.write(imu, imu_log[result.imu_messages].t_ns, ros::serializeImu(imu_log[result.imu_messages], "imu0"));
    for (std::size_t& g = result.groundtruth_messages; g < truth.size() && truth[g].t_ns <= t; ++g)
      bag.write(gt, truth[g].t_ns, ros::serializePoseStamped(truth[g].t_ns, "world", truth[g].T_w_b));
  };
  for (std::size_t i = 0; i < seq.frameCount(); ++i) {
    const std::int64_t t = seq.frameTime(i);
    const std::optional<cv::Mat> left = seq.leftImage(i);
    const cv::Mat right = seq.rightImageLoader(i)();
    writeUntil(t);
    if (left && !right.empty()) {
      bag.write(cam[0], t, image(t, *left, "cam0"));
      bag.write(cam[1], t, image(t, right, "cam1"));
      ++result.stereo_frames;
    }
    if (progress) progress(i + 1, seq.frameCount());
  }
  writeUntil(INT64_MAX);
  bag.close();
  camera::StereoRig rig = seq.calibration();
  rig.topic[0] = result.topics.cam0;
  rig.topic[1] = result.topics.cam1;
  rig.imu_topic = result.topics.imu;
  result.camchain_yaml = (dir / "camchain-imucam.yaml").string();
  result.imu_yaml = (dir / "imu.yaml").string();
  writeKalibrCalibration(result.camchain_yaml, result.imu_yaml, rig);
  return result;
}

}  // namespace edgevio::io
