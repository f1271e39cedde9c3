#include "edgevio/io/bag_sequence.h"

#include <algorithm>
#include <filesystem>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/time.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/io/ros_messages.h"

namespace edgevio::io {

namespace fs = std::filesystem;

namespace {

const std::vector<std::string> kImageTypes = {ros::kImage, ros::kCompressedImage};
const std::vector<std::string> kPoseTypes = {ros::kPoseStamped, ros::kTransformStamped, ros::kOdometry};
// What to do when a bag read for its poses or IMU alone has several such topics.
constexpr const char* kOneTopic = "a bag read as a trajectory or an IMU log needs exactly one such topic (ROS's rosbag filter makes one)";

bool oneOf(const std::string& type, const std::vector<std::string>& types) {
  return std::find(types.begin(), types.end(), type) != types.end();
}

std::string joined(const std::vector<std::string>& v) {
  std::string s;
  for (const std::string& x : v) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "none" : s;
}

/// The calibration for a bag: the one given, else Kalibr's files or an ASL folder beside it.
camera::StereoRig bagCalibration(const std::string& bag, const std::string& calib) {
  if (!calib.empty()) return loadCalibration(calib);
  const fs::path dir = fs::absolute(bag).parent_path();
  if (fs::exists(dir / "camchain-imucam.yaml")) return loadCalibration((dir / "camchain-imucam.yaml").string());
  if (fs::is_directory(dir / "mav0" / "cam0")) return loadCalibration(dir.string());
  throw InputError(bag, 0,
                   "no calibration beside the bag: put Kalibr's camchain-imucam.yaml (with imu.yaml) in " + dir.string() +
                       ", or pass --calib FILE (a camchain-imucam.yaml, or an ASL folder with sensor.yaml files)");
}

/// How likely a topic's name says it is the left camera (higher) or the right one.
int leftness(const std::string& topic) {
  for (const char* left : {"cam0", "left", "infra1"})
    if (topic.find(left) != std::string::npos) return 1;
  for (const char* right : {"cam1", "right", "infra2"})
    if (topic.find(right) != std::string::npos) return -1;
  return 0;
}

/// Orders a topic's messages by their record time (the index messages are numbered by).
template <class T>
void sortByRecordTime(std::vector<std::pair<BagMessageRef, T>>* items) {
  std::stable_sort(items->begin(), items->end(), [](const auto& a, const auto& b) { return a.first.record_time_ns < b.first.record_time_ns; });
}


/// One IMU message; InputError naming `where` when it does not parse.
imu::ImuSample imuMessage(RosbagReader& reader, const BagMessageRef& ref, const std::string& where) {
  imu::ImuSample s;
  if (!ros::parseImu(reader.read(ref), &s)) throw InputError(where + ": not a complete sensor_msgs/Imu with finite values");
  return s;
}

/// One ground-truth message (PoseStamped, TransformStamped or Odometry); InputError naming `where` when it does not parse.
TrajectorySample poseMessage(RosbagReader& reader, const BagMessageRef& ref, const std::string& where) {
  TrajectorySample s;
  const std::string& type = reader.connection(ref.connection)->type;
  if (!ros::parsePose(reader.read(ref), type, &s.t_ns, &s.T_w_b)) throw InputError(where + ": not a complete " + type);
  return s;
}

/// Ground truth in stamp order, one sample per stamp.
Trajectory byStamp(std::vector<TrajectorySample> samples) {
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.t_ns < b.t_ns; });
  Trajectory out;
  for (const TrajectorySample& s : samples)
    if (out.empty() || s.t_ns > out.back().t_ns) out.push_back(s);
  return out;
}

/// The distinct topics of the bag's connections of one of `types`.
std::vector<std::string> topicsOf(const RosbagReader& reader, const std::vector<std::string>& types) {
  std::vector<std::string> topics;
  for (const BagConnection& c : reader.connections())
    if (oneOf(c.type, types) && std::find(topics.begin(), topics.end(), c.topic) == topics.end()) topics.push_back(c.topic);
  return topics;
}

/// `given`, else the bag's only topic of `types`; InputError naming the option to pass.
std::string theTopic(const RosbagReader& reader, const std::string& given, const std::vector<std::string>& types, const char* what,
                     const char* option) {
  if (!given.empty()) return given;
  const std::vector<std::string> topics = topicsOf(reader, types);
  if (topics.size() != 1)
    throw InputError(reader.path(), 0, "found " + std::to_string(topics.size()) + " " + what + " topics (" + joined(topics) + "): pass " + option);
  return topics[0];
}

/// The messages on `topic`, which must be of one of `types`, in file order.
std::vector<BagMessageRef> messagesOn(const RosbagReader& reader, const std::string& topic, const std::vector<std::string>& types) {
  std::vector<BagMessageRef> out;
  for (const BagMessageRef& ref : reader.messagesInFileOrder()) {
    const BagConnection* c = reader.connection(ref.connection);
    if (c && c->topic == topic && oneOf(c->type, types)) out.push_back(ref);
  }
  if (out.empty()) throw InputError(reader.path(), 0, "no " + joined(types) + " messages on topic " + topic);
  return out;
}

}  // namespace

BagSequence::BagSequence(const SequenceSource& source, const DatasetOptions& options)
    : path_(source.path), reader_(std::make_unique<RosbagReader>(source.path)) {
  warnings_ = reader_->warnings();
  rig_ = bagCalibration(source.path, source.calib);
  warnings_.insert(warnings_.end(), rig_.warnings.begin(), rig_.warnings.end());
  chooseTopics(source.topics);
  readMessages(options);
  std::vector<std::int64_t> tl, tr;
  for (const ImageRef& r : left_) tl.push_back(r.stamp_ns);
  for (const ImageRef& r : right_) tr.push_back(r.stamp_ns);
  std::size_t unpaired[2] = {0, 0};
  pairs_ = pairStereo(tl, tr, toNanoseconds(options.stereo_sync_tolerance_s), unpaired);
  for (int cam = 0; cam < 2; ++cam)
    if (unpaired[cam] > 0)
      warnings_.push_back(path_ + ": " + std::to_string(unpaired[cam]) + " image(s) of " + (cam == 0 ? topics_.cam0 : topics_.cam1) +
                          " without a partner on the other camera's topic within " +
                          std::to_string(options.stereo_sync_tolerance_s) + " s, skipped");
}

std::string BagSequence::name() const { return fs::path(path_).stem().string(); }

std::string BagSequence::location() const { return fs::absolute(path_).lexically_normal().string(); }

std::vector<std::uint32_t> BagSequence::connectionsOf(const std::string& topic, const std::vector<std::string>& types,
                                                      const char* what) const {
  std::vector<std::string> topics;
  std::vector<std::uint32_t> ids;
  for (const BagConnection& c : reader_->connections()) {
    topics.push_back(c.topic + " (" + c.type + ")");
    if (c.topic != topic) continue;
    if (!oneOf(c.type, types))
      throw InputError(path_, 0, "topic " + topic + " is a " + c.type + ", not a " + what + " topic (" + joined(types) + ")");
    ids.push_back(c.id);
  }
  if (ids.empty()) throw InputError(path_, 0, "no topic " + topic + " for the " + what + " messages; the bag has: " + joined(topics));
  return ids;
}

void BagSequence::chooseTopics(const BagTopics& given) {
  topics_ = given;
  std::vector<std::string> images = topicsOf(*reader_, kImageTypes);
  if (topics_.cam0.empty() != topics_.cam1.empty())
    throw InputError(path_, 0, "give both --cam0-topic and --cam1-topic, or neither (then they are found by type)");
  if (topics_.cam0.empty()) {
    if (images.size() != 2)
      throw InputError(path_, 0, "found " + std::to_string(images.size()) + " image topics (" + joined(images) +
                                     "): pass --cam0-topic and --cam1-topic");
    // The left camera: the one the calibration names cam0's, else by name.
    const bool named = !rig_.topic[0].empty() && (images[0] == rig_.topic[0] || images[1] == rig_.topic[0]);
    if (named ? images[1] == rig_.topic[0] : leftness(images[1]) > leftness(images[0])) std::swap(images[0], images[1]);
    topics_.cam0 = images[0];
    topics_.cam1 = images[1];
  }
  topics_.imu = theTopic(*reader_, topics_.imu, {ros::kImu}, "IMU", "--imu-topic");
  if (topics_.groundtruth.empty()) {  // the one pose topic, if there is exactly one
    const std::vector<std::string> poses = topicsOf(*reader_, kPoseTypes);
    if (poses.size() == 1) topics_.groundtruth = poses[0];
  }
  image_connections_[0] = connectionsOf(topics_.cam0, kImageTypes, "camera");
  image_connections_[1] = connectionsOf(topics_.cam1, kImageTypes, "camera");
  imu_connections_ = connectionsOf(topics_.imu, {ros::kImu}, "IMU");
  if (!topics_.groundtruth.empty()) groundtruth_connections_ = connectionsOf(topics_.groundtruth, kPoseTypes, "ground-truth");
}

Trajectory readBagTrajectory(const std::string& bag, const std::string& topic) {
  RosbagReader reader(bag);
  const std::string t = theTopic(reader, topic, kPoseTypes, "pose", kOneTopic);
  std::vector<TrajectorySample> samples;
  for (const BagMessageRef& ref : messagesOn(reader, t, kPoseTypes))
    samples.push_back(poseMessage(reader, ref, bag + ", topic " + t + ", message " + std::to_string(samples.size())));
  return byStamp(std::move(samples));
}

std::vector<imu::ImuSample> readBagImu(const std::string& bag, const std::string& topic) {
  RosbagReader reader(bag);
  const std::string t = theTopic(reader, topic, {ros::kImu}, "IMU", kOneTopic);
  std::vector<imu::ImuSample> samples;
  for (const BagMessageRef& ref : messagesOn(reader, t, {ros::kImu}))
    samples.push_back(imuMessage(reader, ref, bag + ", topic " + t + ", message " + std::to_string(samples.size())));
  std::stable_sort(samples.begin(), samples.end(), [](const auto& a, const auto& b) { return a.t_ns < b.t_ns; });
  return samples;
}

void BagSequence::readMessages(const DatasetOptions& options) {
  std::vector<std::pair<BagMessageRef, std::int64_t>> images[2];
  std::vector<std::pair<BagMessageRef, imu::ImuSample>> imu;
  std::vector<TrajectorySample> gt;
  const auto on = [](const std::vector<std::uint32_t>& ids, const BagMessageRef& ref) {
    return std::find(ids.begin(), ids.end(), ref.connection) != ids.end();
  };
  for (const BagMessageRef& ref : reader_->messagesInFileOrder()) {
    const auto where = [&](const std::string& topic, std::size_t n) { return path_ + ", topic " + topic + ", message " + std::to_string(n); };
    for (int cam = 0; cam < 2; ++cam)
      if (on(image_connections_[cam], ref)) {
        std::int64_t stamp = 0;
        if (!ros::parseHeaderStamp(reader_->read(ref, ros::kHeaderStampBytes), &stamp))
          throw InputError(where(cam == 0 ? topics_.cam0 : topics_.cam1, images[cam].size()) + ": too short for a header");
        images[cam].emplace_back(ref, stamp);
      }
    if (on(imu_connections_, ref)) imu.emplace_back(ref, imuMessage(*reader_, ref, where(topics_.imu, imu.size())));
    if (on(groundtruth_connections_, ref)) gt.push_back(poseMessage(*reader_, ref, where(topics_.groundtruth, gt.size())));
  }
  for (int cam = 0; cam < 2; ++cam) {
    // A stamp that repeats or goes back (a driver's clock glitch) loses its
    // image, with a warning, as in an ASL folder.
    sortByRecordTime(&images[cam]);
    std::int64_t last = -1;
    for (std::size_t k = 0; k < images[cam].size(); ++k) {
      const auto& [ref, stamp] = images[cam][k];
      if (stamp <= last) {
        ++out_of_order_[cam];
        warnings_.push_back(path_ + ", topic " + (cam == 0 ? topics_.cam0 : topics_.cam1) + ", message " + std::to_string(k) + ": " +
                            (stamp == last ? "duplicate" : "decreasing") + " header stamp, image skipped");
        continue;
      }
      last = stamp;
      (cam == 0 ? left_ : right_).push_back({ref, stamp, k});
    }
  }
  sortByRecordTime(&imu);
  for (std::size_t k = 0; k < imu.size(); ++k) {
    const std::int64_t dt = k == 0 ? 1 : imu[k].second.t_ns - imu[k - 1].second.t_ns;
    if (dt <= 0)
      throw InputError(path_ + ", topic " + topics_.imu + ", message " + std::to_string(k) + ": " + (dt == 0 ? "duplicate" : "decreasing") +
                       " header stamp");
    imu_.push_back(imu[k].second);
  }
  checkImu(options);
  prepareImuLog(&imu_, rig_, options, path_ + ", topic " + topics_.imu, &warnings_);
  ground_truth_ = byStamp(std::move(gt));
}

void BagSequence::checkImu(const DatasetOptions& options) {
  if (imu_.size() < 2) throw InputError(path_, 0, "topic " + topics_.imu + " has fewer than 2 IMU messages");
  const auto gap_ns = toNanoseconds(options.imu_gap_warning_s);
  for (std::size_t k = 1; k < imu_.size(); ++k) {
    const std::int64_t dt = imu_[k].t_ns - imu_[k - 1].t_ns;
    if (dt <= gap_ns) continue;
    warnings_.push_back(path_ + ", topic " + topics_.imu + ", message " + std::to_string(k) +
                        formatText(": IMU gap of %.3f s before t = %.3f s", toSeconds(dt), toSeconds(imu_[k].t_ns)));
  }
}

cv::Mat BagSequence::decode(int cam, const ImageRef& image) const {
  const std::string& type = reader_->connection(image.ref.connection)->type;
  const std::string where = "topic " + (cam == 0 ? topics_.cam0 : topics_.cam1) + ", message " + std::to_string(image.index);
  ros::ImageMessage m;
  std::vector<std::uint8_t> bytes;
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    bytes = reader_->read(image.ref);
  }
  if (!ros::parseImage(bytes, type, &m)) throw InputError(path_, 0, where + ": not a complete " + type);
  std::string error;
  cv::Mat gray = ros::toGray(m, &error);
  if (gray.empty()) throw InputError(path_, 0, where + ": " + error);
  const camera::CameraModel& model = rig_.cam[cam];
  if (gray.cols != model.width || gray.rows != model.height)
    throw InputError(path_, 0, where + ": the image is " + std::to_string(gray.cols) + "x" + std::to_string(gray.rows) +
                                   ", the calibration's cam" + std::to_string(cam) + " " + std::to_string(model.width) + "x" +
                                   std::to_string(model.height) + " (wrong calibration, or wrong topic?)");
  return gray;
}

std::optional<cv::Mat> BagSequence::leftImage(std::size_t i) { return decode(0, left_.at(pairs_.at(i).first)); }

std::function<cv::Mat()> BagSequence::rightImageLoader(std::size_t i) const {
  const ImageRef image = right_.at(pairs_.at(i).second);
  return [this, image] {
    try {
      return decode(1, image);
    } catch (const InputError&) {  // a keyframe without depth, reported as such by the pipeline
      return cv::Mat();
    }
  };
}

std::unique_ptr<Sequence> openSequence(const SequenceSource& source, const DatasetOptions& options) {
  if (!fs::is_directory(source.path) && RosbagReader::looksLikeBag(source.path)) return std::make_unique<BagSequence>(source, options);
  if (!source.calib.empty() || !source.topics.cam0.empty() || !source.topics.imu.empty() || !source.topics.groundtruth.empty())
    throw InputError(source.path, 0, "--calib and the --*-topic options are for ROS bags; an ASL folder has its own calibration");
  return std::make_unique<EurocDataset>(source.path, options);
}

}  // namespace edgevio::io
