// A ROS 1 bag as a sequence: a bag exported from an ASL folder reads back as
// that folder, pixel for pixel and sample for sample, through edgevio's
// writer and through ROS's own (Debian's python3-rosbag); every bad input
// gives an InputError naming the bag, the topic and the message.
#include "edgevio/io/bag_sequence.h"

#include <gtest/gtest.h>
#include <zlib.h>

#include <opencv2/core.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

#include "common/mini_dataset.h"
#include "common/test_support.h"
#include "edgevio/common/error.h"
#include "edgevio/io/bag_export.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/io/ros_messages.h"
#include "edgevio/io/rosbag_writer.h"
#include "edgevio/io/trajectory_io.h"

namespace edgevio::io {
namespace {

using test::expectInputError;
using test::TempDir;

/// The mini ASL folder of 8 patterned frames.
std::string miniFolder(const TempDir& dir) {
  test::MiniDatasetSpec spec;
  spec.frames = 8;
  spec.patterned = true;
  return test::writeMiniDataset(dir, spec);
}

/// Both sequences give the same frames (times and pixels), IMU and ground truth.
void expectSameSequence(Sequence& bag, Sequence& folder, double pose_tolerance = 0.0) {
  ASSERT_EQ(bag.frameCount(), folder.frameCount());
  for (std::size_t i = 0; i < folder.frameCount(); ++i) {
    EXPECT_EQ(bag.frameTime(i), folder.frameTime(i)) << i;
    const std::optional<cv::Mat> a = bag.leftImage(i), b = folder.leftImage(i);
    ASSERT_TRUE(a && b) << i;
    EXPECT_EQ(cv::norm(*a, *b, cv::NORM_INF), 0.0) << "left image " << i;
    EXPECT_EQ(cv::norm(bag.rightImageLoader(i)(), folder.rightImageLoader(i)(), cv::NORM_INF), 0.0) << "right image " << i;
  }
  ASSERT_EQ(bag.imu().size(), folder.imu().size());
  for (std::size_t k = 0; k < folder.imu().size(); ++k) {
    EXPECT_EQ(bag.imu()[k].t_ns, folder.imu()[k].t_ns);
    EXPECT_EQ(bag.imu()[k].gyro, folder.imu()[k].gyro);
    EXPECT_EQ(bag.imu()[k].accel, folder.imu()[k].accel);
  }
  ASSERT_EQ(bag.groundTruth().size(), folder.groundTruth().size());
  for (std::size_t k = 0; k < folder.groundTruth().size(); ++k) {
    const geometry::SE3 d = bag.groundTruth()[k].T_w_b.inverse() * folder.groundTruth()[k].T_w_b;
    EXPECT_LE(d.translation().norm(), pose_tolerance) << k;
    EXPECT_LE(geometry::angle(d.so3()), pose_tolerance + 1e-15) << k;
  }
  EXPECT_EQ(bag.calibration().cam[0].fx, folder.calibration().cam[0].fx);
}

TEST(BagSequence, AnExportedFolderReadsBackAsTheFolderInEveryFormat) {
  TempDir data;
  const std::string folder = miniFolder(data);
  EurocDataset original(folder, DatasetOptions{});
  for (BagCompression c : {BagCompression::kNone, BagCompression::kBz2, BagCompression::kLz4})
    for (BagImages images : {BagImages::kRaw, BagImages::kPng}) {
      TempDir out;
      Sequence& source = original;
      const BagExport e = exportBag(source, out.file("mini.bag"), {c, images});
      EXPECT_EQ(e.stereo_frames, 8u);
      // The calibration edgevio finds beside it: Kalibr's files, which store
      // the inverse transforms, so equal to rounding.
      BagSequence beside({out.file("mini.bag"), "", {}}, DatasetOptions{});
      EXPECT_EQ(beside.topics().cam0, "/cam0/image_raw");
      EXPECT_EQ(beside.topics().groundtruth, "/groundtruth");
      for (int cam = 0; cam < 2; ++cam)
        EXPECT_LT((beside.calibration().T_b_c[cam].matrix() - original.calibration().T_b_c[cam].matrix()).norm(), 1e-15);
      // With the folder's calibration: the folder, exactly.
      BagSequence bag({out.file("mini.bag"), folder, {}}, DatasetOptions{});
      EurocDataset again(folder, DatasetOptions{});
      expectSameSequence(bag, again);
    }
}

TEST(BagSequence, TopicsAreFoundByTypeAndNameOrGiven) {
  TempDir data, out;
  EurocDataset folder(miniFolder(data), DatasetOptions{});
  RosbagWriter w(out.file("named.bag"), BagCompression::kNone);
  // Right first, names that say which is which, no calibration topics.
  const std::uint32_t right = w.addConnection("/stereo/right/image", ros::kImage), left = w.addConnection("/stereo/left/image", ros::kImage);
  const std::uint32_t imu = w.addConnection("/mavros/imu/data_raw", ros::kImu);
  for (const auto& s : folder.imu()) w.write(imu, s.t_ns, ros::serializeImu(s, "imu"));
  for (std::size_t i = 0; i < folder.frameCount(); ++i) {
    w.write(left, folder.frameTime(i), ros::serializeImage(folder.frameTime(i), "l", *folder.leftImage(i)));
    w.write(right, folder.frameTime(i), ros::serializeImage(folder.frameTime(i), "r", folder.rightImageLoader(i)()));
  }
  w.close();
  BagSequence found({out.file("named.bag"), data.path(), {}}, DatasetOptions{});
  EXPECT_EQ(found.topics().cam0, "/stereo/left/image");
  EXPECT_EQ(found.topics().cam1, "/stereo/right/image");
  EXPECT_EQ(found.topics().imu, "/mavros/imu/data_raw");
  EXPECT_EQ(found.topics().groundtruth, "");
  EXPECT_EQ(cv::norm(*found.leftImage(3), *folder.leftImage(3), cv::NORM_INF), 0.0);
  // Given the other way round, they are taken as given.
  BagSequence given({out.file("named.bag"), data.path(), {"/stereo/right/image", "/stereo/left/image", "", ""}}, DatasetOptions{});
  EXPECT_EQ(cv::norm(*given.leftImage(3), folder.rightImageLoader(3)(), cv::NORM_INF), 0.0);
}

/// A bag from the mini folder with one thing changed by `edit`, which writes messages itself.
std::string bagWith(const TempDir& out, const std::string& name, const std::function<void(RosbagWriter&, EurocDataset&)>& edit) {
  TempDir data;
  EurocDataset folder(miniFolder(data), DatasetOptions{});
  RosbagWriter w(out.file(name), BagCompression::kNone);
  edit(w, folder);
  w.close();
  // The calibration beside it: the mini folder's.
  if (!std::filesystem::exists(out.path() + "/mav0"))
    std::filesystem::copy(data.path() + "/mav0", out.path() + "/mav0", std::filesystem::copy_options::recursive);
  return out.file(name);
}

void writeImages(RosbagWriter& w, EurocDataset& folder, const std::function<cv::Mat(int cam, std::size_t i, const cv::Mat&)>& change = {}) {
  const std::uint32_t ids[2] = {w.addConnection("/cam0/image_raw", ros::kImage), w.addConnection("/cam1/image_raw", ros::kImage)};
  for (std::size_t i = 0; i < folder.frameCount(); ++i)
    for (int cam = 0; cam < 2; ++cam) {
      const cv::Mat img = cam == 0 ? *folder.leftImage(i) : folder.rightImageLoader(i)();
      w.write(ids[cam], folder.frameTime(i), ros::serializeImage(folder.frameTime(i), "c", change ? change(cam, i, img) : img));
    }
}

void writeImu(RosbagWriter& w, EurocDataset& folder, const std::string& topic = "/imu0") {
  const std::uint32_t id = w.addConnection(topic, ros::kImu);
  for (const auto& s : folder.imu()) w.write(id, s.t_ns, ros::serializeImu(s, "imu"));
}

TEST(BagSequence, BadBagsAreErrorsNamingTheBagTopicAndMessage) {
  TempDir out;
  const auto open = [](const std::string& bag, BagTopics topics = {}) {
    return [bag, topics] {
      BagSequence s({bag, "", topics}, DatasetOptions{});
      for (std::size_t i = 0; i < s.frameCount(); ++i) s.leftImage(i);
    };
  };
  const std::string no_imu = bagWith(out, "no_imu.bag", [](RosbagWriter& w, EurocDataset& f) { writeImages(w, f); });
  expectInputError(open(no_imu), {no_imu, "found 0 IMU topics", "--imu-topic"});
  expectInputError(open(no_imu, {"", "", "/imu", ""}), {no_imu, "no topic /imu", "/cam0/image_raw (sensor_msgs/Image)"});
  const std::string two_imus = bagWith(out, "two_imus.bag", [](RosbagWriter& w, EurocDataset& f) {
    writeImages(w, f);
    writeImu(w, f, "/imu0");
    writeImu(w, f, "/imu1");
  });
  expectInputError(open(two_imus), {two_imus, "found 2 IMU topics (/imu0, /imu1)", "--imu-topic"});
  expectInputError(open(two_imus, {"/imu0", "/cam1/image_raw", "/imu1", ""}), {two_imus, "topic /imu0 is a sensor_msgs/Imu, not a camera topic"});
  const std::string small = bagWith(out, "small.bag", [](RosbagWriter& w, EurocDataset& f) {
    writeImages(w, f, [](int cam, std::size_t i, const cv::Mat& m) { return cam == 0 && i == 5 ? m(cv::Rect(0, 0, 32, 24)).clone() : m; });
    writeImu(w, f);
  });
  expectInputError(open(small), {small, "topic /cam0/image_raw, message 5", "32x24", "64x48"});
  const std::string bayer = bagWith(out, "bayer.bag", [](RosbagWriter& w, EurocDataset& f) {
    const std::uint32_t ids[2] = {w.addConnection("/cam0/image_raw", ros::kImage), w.addConnection("/cam1/image_raw", ros::kImage)};
    writeImu(w, f);
    for (std::size_t i = 0; i < f.frameCount(); ++i)
      for (const std::uint32_t id : ids) {
        std::vector<std::uint8_t> m = ros::serializeImage(f.frameTime(i), "c", *f.leftImage(i));
        const std::string mono8 = "mono8", bayer8 = "bggr8";  // same length: the message stays well formed
        std::copy(bayer8.begin(), bayer8.end(), std::search(m.begin(), m.end(), mono8.begin(), mono8.end()));
        w.write(id, f.frameTime(i), m);
      }
  });
  expectInputError(open(bayer), {bayer, "topic /cam0/image_raw, message 0", "encoding 'bggr8'"});
  const std::string cut = bagWith(out, "cut_imu.bag", [](RosbagWriter& w, EurocDataset& f) {
    writeImages(w, f);
    const std::uint32_t id = w.addConnection("/imu0", ros::kImu);
    for (std::size_t k = 0; k < f.imu().size(); ++k) {
      std::vector<std::uint8_t> m = ros::serializeImu(f.imu()[k], "imu");
      if (k == 17) m.resize(m.size() - 8);
      w.write(id, f.imu()[k].t_ns, m);
    }
  });
  expectInputError(open(cut), {cut, "topic /imu0, message 17", "not a complete sensor_msgs/Imu"});
}

TEST(BagSequence, ARepeatedImageStampSkipsTheImageWithAWarning) {
  // Left image 4 carries image 3's stamp (a driver's clock glitch): it is
  // skipped and counted, and the right image 4 has no partner.
  TempDir out;
  std::size_t frames = 0;
  const std::string bag = bagWith(out, "repeat.bag", [&](RosbagWriter& w, EurocDataset& f) {
    frames = f.frameCount();
    const std::uint32_t ids[2] = {w.addConnection("/cam0/image_raw", ros::kImage), w.addConnection("/cam1/image_raw", ros::kImage)};
    for (std::size_t i = 0; i < f.frameCount(); ++i)
      for (int cam = 0; cam < 2; ++cam) {
        const std::int64_t stamp = cam == 0 && i == 4 ? f.frameTime(3) : f.frameTime(i);
        w.write(ids[cam], f.frameTime(i), ros::serializeImage(stamp, "c", cam == 0 ? *f.leftImage(i) : f.rightImageLoader(i)()));
      }
    writeImu(w, f);
  });
  BagSequence s({bag, "", {}}, DatasetOptions{});
  EXPECT_EQ(s.frameCount(), frames - 1);
  EXPECT_EQ(s.unreadableImages(), 1u);
  std::string all;
  for (const std::string& w : s.warnings()) all += w + "\n";
  test::expectContainsAll(all, {"topic /cam0/image_raw, message 4: duplicate header stamp, image skipped"});
}

TEST(BagSequence, AMissingCalibrationSaysWhichFilesAndWhatToPass) {
  TempDir data, out;
  EurocDataset folder(miniFolder(data), DatasetOptions{});
  exportBag(folder, out.file("a.bag"), {});
  std::filesystem::remove(out.file("camchain-imucam.yaml"));
  expectInputError([&] { BagSequence s({out.file("a.bag"), "", {}}, DatasetOptions{}); },
                   {out.file("a.bag"), "no calibration beside the bag", "camchain-imucam.yaml", "--calib"});
  expectInputError([&] { BagSequence s({out.file("a.bag"), out.file("nothing.yaml"), {}}, DatasetOptions{}); }, {"nothing.yaml"});
  // Folder options are for bags only.
  expectInputError([&] { openSequence({data.path(), out.file("x.yaml"), {}}, DatasetOptions{}); }, {"for ROS bags"});
}

TEST(BagSequence, ABagsPosesAndImuReadAloneAsTheFoldersFiles) {
  TempDir data, out;
  EurocDataset folder(miniFolder(data), DatasetOptions{});
  exportBag(folder, out.file("a.bag"), {BagCompression::kLz4, BagImages::kPng});
  // What `eval --gt X.bag` and `simulate --trajectory X.bag --imu X.bag` read.
  const Trajectory poses = readTrajectory(out.file("a.bag"));
  ASSERT_EQ(poses.size(), folder.groundTruth().size());
  for (std::size_t k = 0; k < poses.size(); ++k) {
    EXPECT_EQ(poses[k].t_ns, folder.groundTruth()[k].t_ns);
    EXPECT_EQ(poses[k].T_w_b.matrix(), folder.groundTruth()[k].T_w_b.matrix()) << k;
  }
  const std::vector<imu::ImuSample> imu = readBagImu(out.file("a.bag"), "/imu0");
  ASSERT_EQ(imu.size(), folder.imu().size());
  for (std::size_t k = 0; k < imu.size(); ++k) {
    EXPECT_EQ(imu[k].t_ns, folder.imu()[k].t_ns);
    EXPECT_EQ(imu[k].gyro, folder.imu()[k].gyro);
    EXPECT_EQ(imu[k].accel, folder.imu()[k].accel);
  }
  // No pose topic, a wrong topic, two IMU topics: errors that say what to pass.
  const std::string no_gt = bagWith(out, "no_gt.bag", [](RosbagWriter& w, EurocDataset& f) {
    writeImu(w, f, "/imu0");
    writeImu(w, f, "/imu1");
  });
  expectInputError([&] { readBagTrajectory(no_gt); }, {no_gt, "found 0 pose topics", "exactly one"});
  expectInputError([&] { readBagTrajectory(no_gt, "/imu0"); }, {no_gt, "/imu0"});
  expectInputError([&] { readBagImu(no_gt); }, {no_gt, "found 2 IMU topics (/imu0, /imu1)", "exactly one"});
  EXPECT_EQ(readBagImu(no_gt, "/imu1").size(), folder.imu().size());
}

// --- Against ROS's own implementation (Debian's python3-rosbag) -------------------

/// Runs the interop script; its output, or nullopt when ROS's Python packages are absent (exit 77).
std::optional<std::string> interop(const std::string& args) {
  const std::string script = test::sourceDir() + "/tests/io/rosbag_interop.py";
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  std::FILE* p = popen((python + " " + script + " " + args + " 2>&1").c_str(), "r");
  if (!p) return std::nullopt;
  std::string out;
  std::array<char, 4096> buf{};
  while (std::fgets(buf.data(), buf.size(), p)) out += buf.data();
  const int status = pclose(p);
  if (WEXITSTATUS(status) == 77) return std::nullopt;
  EXPECT_EQ(WEXITSTATUS(status), 0) << out;
  return out;
}
/// Skips the test, saying what to install, when ROS's Python packages are absent.
#define EDGEVIO_REQUIRE_ROS_PYTHON()                                                  \
  if (!interop("probe").has_value())                                                  \
  GTEST_SKIP() << "skipped: Debian's python3-rosbag, python3-sensor-msgs and python3-nav-msgs " \
                  "are not installed (scripts/setup.sh installs them)"

TEST(BagSequence, BagsWrittenByRosPythonReadAsTheFolder) {
  TempDir data;
  const std::string folder = miniFolder(data);
  EDGEVIO_REQUIRE_ROS_PYTHON();
  int k = 0;
  for (const char* compression : {"none", "bz2", "lz4"})
    for (const char* images : {"raw", "png"}) {
      const char* groundtruth = std::array{"pose", "transform", "odometry"}[k++ % 3];
      TempDir out;
      const std::string bag = out.file("ros.bag");
      ASSERT_TRUE(interop("write " + folder + " " + bag + " " + compression + " " + images + " " + groundtruth).has_value());
      BagSequence from_ros({bag, folder, {}}, DatasetOptions{});
      EurocDataset again(folder, DatasetOptions{});
      SCOPED_TRACE(std::string(compression) + ", " + images + ", ground truth as " + groundtruth);
      // The ground truth's quaternion went through text (the CSV) both ways: equal to rounding.
      expectSameSequence(from_ros, again, 1e-15);
    }
}

TEST(BagSequence, RosPythonReadsEdgevioBags) {
  EDGEVIO_REQUIRE_ROS_PYTHON();
  TempDir data;
  EurocDataset folder(miniFolder(data), DatasetOptions{});
  for (BagCompression c : {BagCompression::kNone, BagCompression::kBz2, BagCompression::kLz4})
    for (BagImages images : {BagImages::kRaw, BagImages::kPng}) {
      TempDir out;
      exportBag(folder, out.file("ours.bag"), {c, images});
      const std::optional<std::string> listing = interop("read " + out.file("ours.bag"));
      ASSERT_TRUE(listing.has_value());
      // What ROS read, per topic, against the folder.
      std::map<std::string, int> count;
      std::istringstream lines(*listing);
      std::string topic, type;
      std::int64_t stamp = 0;
      while (lines >> topic >> type >> stamp) {
        const int k = count[topic]++;
        std::string rest;
        std::getline(lines, rest);
        std::istringstream v(rest);
        if (topic == "/imu0") {
          double w[6];
          for (double& x : w) v >> x;
          EXPECT_EQ(stamp, folder.imu()[k].t_ns);
          EXPECT_EQ(Vec3(w[0], w[1], w[2]), folder.imu()[k].gyro);
          EXPECT_EQ(Vec3(w[3], w[4], w[5]), folder.imu()[k].accel);
        } else if (topic == "/cam0/image_raw" || topic == "/cam1/image_raw") {
          int width = 0, height = 0;
          unsigned long adler = 0;
          v >> width >> height >> adler;
          const cv::Mat img = topic == "/cam0/image_raw" ? *folder.leftImage(k) : folder.rightImageLoader(k)();
          EXPECT_EQ(stamp, folder.frameTime(k));
          EXPECT_EQ(type, images == BagImages::kRaw ? ros::kImage : ros::kCompressedImage);
          EXPECT_EQ(width, img.cols);
          EXPECT_EQ(height, img.rows);
          EXPECT_EQ(adler, adler32(adler32(0, nullptr, 0), img.data, static_cast<uInt>(img.total()))) << topic << " " << k;
        } else {
          EXPECT_EQ(topic, "/groundtruth");
          EXPECT_EQ(stamp, folder.groundTruth()[k].t_ns);
        }
      }
      EXPECT_EQ(count["/cam0/image_raw"], 8);
      EXPECT_EQ(count["/cam1/image_raw"], 8);
      EXPECT_EQ(count["/imu0"], static_cast<int>(folder.imu().size()));
      EXPECT_EQ(count["/groundtruth"], 8);
    }
}

}  // namespace
}  // namespace edgevio::io
