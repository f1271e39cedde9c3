#include "fuzz/fuzz_targets.h"

#include <opencv2/imgcodecs.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <unistd.h>

#include "edgevio/common/error.h"
#include "edgevio/config/config.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/io/imu_io.h"
#include "edgevio/io/png_reader.h"
#include "edgevio/io/ros_messages.h"
#include "edgevio/io/rosbag.h"
#include "edgevio/io/rosbag_writer.h"
#include "edgevio/io/trajectory_io.h"

namespace edgevio::fuzz {
namespace {

namespace fs = std::filesystem;

/// A folder of this process for the files the readers are given (in memory
/// under /dev/shm where there is one: a fuzzer writes one per input).
class Scratch {
 public:
  Scratch() {
    const fs::path base = fs::is_directory("/dev/shm") ? fs::path("/dev/shm") : fs::temp_directory_path();
    dir_ = base / ("edgevio-fuzz-" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  ~Scratch() {
    std::error_code ignored;
    fs::remove_all(dir_, ignored);
  }
  /// Writes the bytes to the file `name` of the folder and returns its path.
  std::string write(const std::string& name, const std::uint8_t* data, std::size_t size) const {
    const std::string path = (dir_ / name).string();
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    if (!out) throw std::runtime_error("fuzz: cannot write " + path);
    return path;
  }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }

 private:
  fs::path dir_;
};

const Scratch& scratch() {
  static const Scratch s;
  return s;
}

Bytes bytesOf(const std::string& text) { return Bytes(text.begin(), text.end()); }

Bytes fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

// --- trajectories (TUM, EuRoC ground truth) ---

io::Trajectory exampleTrajectory() {
  io::Trajectory t;
  for (int i = 0; i < 6; ++i) {
    io::TrajectorySample s;
    s.t_ns = 1403636579763555584 + i * 5000000LL;
    s.T_w_b = geometry::SE3(geometry::SO3::exp(Vec3(0.01 * i, -0.02, 0.3)), Vec3(0.1 * i, 2.0 - i, 0.5));
    s.v_w = Vec3(1.0, -0.5, 0.1 * i);
    s.b_g = Vec3(-0.002, 0.02, 0.07);
    s.b_a = Vec3(-0.01, 0.1, 0.07);
    t.push_back(s);
  }
  return t;
}

void readTrajectoryBytes(const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch().write("trajectory.txt", data, size);
  io::readTrajectory(path);
}

std::vector<Bytes> trajectorySeeds() {
  const std::string tum = scratch().path("seed_tum.txt"), euroc = scratch().path("seed_euroc.csv");
  io::writeTrajectoryTum(tum, exampleTrajectory());
  io::writeTrajectoryEuroc(euroc, exampleTrajectory());
  return {fileBytes(tum), fileBytes(euroc)};
}

// --- IMU (EuRoC imu0/data.csv) ---

void readImuBytes(const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch().write("imu.csv", data, size);
  std::vector<std::string> warnings;
  io::readImuCsv(path, 0.05, &warnings);
}

std::vector<Bytes> imuSeeds() {
  std::vector<imu::ImuSample> samples;
  for (int i = 0; i < 8; ++i) {
    imu::ImuSample s;
    s.t_ns = 1403636579758555392 + i * 5000000LL;
    s.gyro = Vec3(-0.099, 0.14 + 0.01 * i, 0.02);
    s.accel = Vec3(8.1, -0.03 * i, -3.3);
    samples.push_back(s);
  }
  const std::string path = scratch().path("seed_imu.csv");
  io::writeImuCsv(path, samples);
  return {fileBytes(path)};
}

// --- the config file ---

void readConfigBytes(const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch().write("config.yaml", data, size);
  loadConfig(path);
}

std::vector<Bytes> configSeeds() {
  std::ostringstream full;
  writeConfig(full, Config{});
  return {bytesOf(full.str()), bytesOf("estimator:\n  window_size: 12\ntracking:\n  lost_after_failures: 5\n")};
}

// --- calibrations: Kalibr camchain, EuRoC cam0/sensor.yaml ---

void readKalibrBytes(const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch().write("camchain.yaml", data, size);
  io::loadKalibrCalibration(path);
}

std::vector<Bytes> kalibrSeeds() {
  const std::string camchain = scratch().path("seed_camchain.yaml"), imu = scratch().path("seed_imu.yaml");
  io::writeKalibrCalibration(camchain, imu, io::eurocDefaultRig());
  return {fileBytes(camchain)};
}

void readEurocCameraBytes(const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch().write("sensor.yaml", data, size);
  camera::CameraModel model;
  geometry::SE3 T_b_c;
  double rate_hz = 0.0;
  io::loadEurocCamera(path, &model, &T_b_c, &rate_hz);
}

std::vector<Bytes> eurocCameraSeeds() {
  const std::string mav0 = scratch().path("seed_mav0");
  io::writeEurocCalibration(mav0, io::eurocDefaultRig());
  return {fileBytes(mav0 + "/cam0/sensor.yaml")};
}

// --- PNG images ---

/// The fast PNG decoder either declines (empty: the caller falls back to
/// OpenCV; here a rejection) or gives exactly OpenCV's image.
void readPngBytes(const std::uint8_t* data, std::size_t size) {
  const Bytes file(data, data + size);
  const cv::Mat fast = io::decodePngGray8(file);
  if (fast.empty()) throw InputError("declined: the caller falls back to OpenCV");
  const cv::Mat reference = cv::imdecode(file, cv::IMREAD_GRAYSCALE);  // as the datasets' fallback reads
  if (reference.empty() || reference.size() != fast.size() ||
      cv::norm(fast, reference, cv::NORM_INF) != 0.0) {
    throw std::logic_error("fuzz png: decodePngGray8 accepted an image OpenCV reads differently");
  }
}

cv::Mat exampleImage(int width, int height) {
  cv::Mat image(height, width, CV_8UC1);
  for (int y = 0; y < height; ++y) {
    for (int x = 0; x < width; ++x) image.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>((x * 37 + y * 11 + x * y) % 251);
  }
  return image;
}

std::vector<Bytes> pngSeeds() {
  std::vector<Bytes> seeds;
  // Each zlib strategy gives other filter and block choices.
  for (int strategy : {cv::IMWRITE_PNG_STRATEGY_DEFAULT, cv::IMWRITE_PNG_STRATEGY_FILTERED, cv::IMWRITE_PNG_STRATEGY_RLE}) {
    Bytes png;
    cv::imencode(".png", exampleImage(23, 9), png, {cv::IMWRITE_PNG_STRATEGY, strategy});
    seeds.push_back(png);
  }
  return seeds;
}

// --- ROS 1 bags and the messages in them ---

void parseMessage(const std::string& type, const Bytes& bytes) {
  if (type == io::ros::kImage || type == io::ros::kCompressedImage) {
    io::ros::ImageMessage image;
    if (io::ros::parseImage(bytes, type, &image)) {
      std::string error;
      io::ros::toGray(image, &error);
    }
  } else if (type == io::ros::kImu) {
    imu::ImuSample s;
    io::ros::parseImu(bytes, &s);
  } else {
    std::int64_t stamp_ns = 0;
    geometry::SE3 T;
    io::ros::parsePose(bytes, type, &stamp_ns, &T);
  }
}

void readRosbagBytes(const std::uint8_t* data, std::size_t size) {
  const std::string path = scratch().write("input.bag", data, size);
  io::RosbagReader reader(path);
  for (const io::BagMessageRef& ref : reader.messagesInFileOrder()) {
    const io::BagConnection* connection = reader.connection(ref.connection);
    if (connection == nullptr) throw std::logic_error("fuzz rosbag: a message refers to a connection the reader does not list");
    parseMessage(connection->type, reader.read(ref));
    parseMessage(connection->type, reader.read(ref, io::ros::kHeaderStampBytes));
  }
}

std::vector<Bytes> rosbagSeeds() {
  std::vector<Bytes> seeds;
  for (io::BagCompression compression : {io::BagCompression::kNone, io::BagCompression::kLz4, io::BagCompression::kBz2}) {
    const std::string path = scratch().path("seed.bag");
    io::RosbagWriter bag(path, compression, 700);  // small chunks: several chunks and their index
    const std::uint32_t cam = bag.addConnection("/cam0/image_raw", io::ros::kImage);
    const std::uint32_t png = bag.addConnection("/cam1/image_raw", io::ros::kCompressedImage);
    const std::uint32_t imu = bag.addConnection("/imu0", io::ros::kImu);
    const std::uint32_t pose = bag.addConnection("/groundtruth", io::ros::kPoseStamped);
    const io::Trajectory truth = exampleTrajectory();
    for (std::size_t i = 0; i < 3; ++i) {
      const std::int64_t t = truth[i].t_ns;
      imu::ImuSample s;
      s.t_ns = t;
      s.gyro = Vec3(0.1, -0.2, 0.05 * static_cast<double>(i));
      s.accel = Vec3(0.2, 9.7, -0.4);
      bag.write(imu, t, io::ros::serializeImu(s, "imu4"));
      bag.write(pose, t, io::ros::serializePoseStamped(t, "world", truth[i].T_w_b));
      bag.write(cam, t, io::ros::serializeImage(t, "cam0", exampleImage(8, 6)));
      bag.write(png, t, io::ros::serializeCompressedPng(t, "cam1", exampleImage(8, 6)));
    }
    bag.close();
    seeds.push_back(fileBytes(path));
  }
  return seeds;
}

}  // namespace

const std::vector<FuzzTarget>& fuzzTargets() {
  static const std::vector<FuzzTarget> targets = {
      {"trajectory", "a trajectory file (TUM or EuRoC ground truth; io::readTrajectory)", readTrajectoryBytes, trajectorySeeds},
      {"imu_csv", "EuRoC imu0/data.csv (io::readImuCsv)", readImuBytes, imuSeeds},
      {"config", "the config file (loadConfig)", readConfigBytes, configSeeds},
      {"kalibr", "a Kalibr camchain (io::loadKalibrCalibration)", readKalibrBytes, kalibrSeeds},
      {"euroc_camera", "EuRoC cam0/sensor.yaml (io::loadEurocCamera)", readEurocCameraBytes, eurocCameraSeeds},
      {"png", "a PNG file (io::decodePngGray8, against OpenCV's decoder)", readPngBytes, pngSeeds},
      {"rosbag", "a ROS 1 bag and its image, IMU and pose messages (io::RosbagReader, io::ros::parse*)", readRosbagBytes,
       rosbagSeeds},
  };
  return targets;
}

const FuzzTarget& fuzzTarget(const std::string& name) {
  std::string names;
  for (const FuzzTarget& t : fuzzTargets()) {
    if (name == t.name) return t;
    names += std::string(names.empty() ? "" : ", ") + t.name;
  }
  throw std::invalid_argument("no fuzz target '" + name + "'; there are: " + names);
}

bool readOrReject(const FuzzTarget& target, const std::uint8_t* data, std::size_t size) {
  try {
    target.read(data, size);
    return true;
  } catch (const InputError&) {
    return false;
  }
}

}  // namespace edgevio::fuzz
