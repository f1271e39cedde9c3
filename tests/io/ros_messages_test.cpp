// ROS 1 message (de)serialisation: round trips, every encoding the bag
// reader converts to grey, and messages cut short at every byte.
#include "edgevio/io/ros_messages.h"

#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstring>

namespace edgevio::io::ros {
namespace {

constexpr std::int64_t kStamp = 1403715273262142976;  // a EuRoC stamp: seconds need all 32 bits of sec

cv::Mat pattern(int rows, int cols) {
  cv::Mat m(rows, cols, CV_8UC1);
  for (int y = 0; y < rows; ++y)
    for (int x = 0; x < cols; ++x) m.at<std::uint8_t>(y, x) = static_cast<std::uint8_t>(3 * x + 11 * y);
  return m;
}

bool equal(const cv::Mat& a, const cv::Mat& b) {
  return a.size() == b.size() && a.type() == b.type() && cv::norm(a, b, cv::NORM_INF) == 0;
}

/// Little-endian bytes for hand-built messages, independent of the serialisers under test.
struct Bytes {
  std::vector<std::uint8_t> b;
  Bytes& u32(std::uint32_t v) {
    for (int k = 0; k < 4; ++k) b.push_back(static_cast<std::uint8_t>(v >> (8 * k)));
    return *this;
  }
  Bytes& u8(std::uint8_t v) {
    b.push_back(v);
    return *this;
  }
  Bytes& f64(double v) {
    std::uint64_t u = 0;
    std::memcpy(&u, &v, 8);
    for (int k = 0; k < 8; ++k) b.push_back(static_cast<std::uint8_t>(u >> (8 * k)));
    return *this;
  }
  Bytes& str(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    b.insert(b.end(), s.begin(), s.end());
    return *this;
  }
  Bytes& header(std::int64_t ns) { return u32(7).u32(static_cast<std::uint32_t>(ns / 1000000000)).u32(static_cast<std::uint32_t>(ns % 1000000000)).str("f"); }
  Bytes& data(const void* p, std::size_t n) {
    u32(static_cast<std::uint32_t>(n));
    const auto* c = static_cast<const std::uint8_t*>(p);
    b.insert(b.end(), c, c + n);
    return *this;
  }
};

std::vector<std::uint8_t> rawImage(const cv::Mat& m, const std::string& encoding, bool big_endian = false) {
  const std::size_t row = m.cols * m.elemSize();
  Bytes out;
  out.header(kStamp).u32(static_cast<std::uint32_t>(m.rows)).u32(static_cast<std::uint32_t>(m.cols)).str(encoding).u8(big_endian).u32(
      static_cast<std::uint32_t>(row));
  return out.data(m.data, row * m.rows).b;
}

cv::Mat gray(const std::vector<std::uint8_t>& bytes, const std::string& type, std::string* error) {
  ImageMessage m;
  EXPECT_TRUE(parseImage(bytes, type, &m));
  EXPECT_EQ(m.stamp_ns, kStamp);
  return toGray(m, error);
}

TEST(RosMessages, ImageAndCompressedImageRoundTrip) {
  const cv::Mat img = pattern(48, 64);
  std::string error;
  EXPECT_TRUE(equal(gray(serializeImage(kStamp, "cam0", img), kImage, &error), img)) << error;
  EXPECT_TRUE(equal(gray(serializeCompressedPng(kStamp, "cam0", img), kCompressedImage, &error), img)) << error;
}

TEST(RosMessages, EveryEncodingBecomesGrey) {
  const cv::Mat img = pattern(20, 30);
  std::string error;
  // mono16 as OpenCV reads a 16-bit PNG (of an ASL folder) as grey.
  cv::Mat wide(20, 30, CV_16UC1);
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 30; ++x) wide.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(2111 * x + 397 * y);
  std::vector<std::uint8_t> png16;
  cv::imencode(".png", wide, png16);
  const cv::Mat as_png = cv::imdecode(png16, cv::IMREAD_GRAYSCALE);
  EXPECT_TRUE(equal(gray(rawImage(wide, "mono16"), kImage, &error), as_png)) << error;
  cv::Mat swapped = wide.clone();
  for (auto it = swapped.begin<std::uint16_t>(); it != swapped.end<std::uint16_t>(); ++it)
    *it = static_cast<std::uint16_t>((*it >> 8) | (*it << 8));
  EXPECT_TRUE(equal(gray(rawImage(swapped, "mono16", true), kImage, &error), as_png)) << error;
  // Colour: OpenCV's own conversion of the same pixels.
  cv::Mat bgr(20, 30, CV_8UC3), expected;
  for (int y = 0; y < 20; ++y)
    for (int x = 0; x < 30; ++x) bgr.at<cv::Vec3b>(y, x) = cv::Vec3b(static_cast<std::uint8_t>(5 * x), static_cast<std::uint8_t>(9 * y), 77);
  cv::cvtColor(bgr, expected, cv::COLOR_BGR2GRAY);
  EXPECT_TRUE(equal(gray(rawImage(bgr, "bgr8"), kImage, &error), expected)) << error;
  cv::Mat rgb;
  cv::cvtColor(bgr, rgb, cv::COLOR_BGR2RGB);
  EXPECT_TRUE(equal(gray(rawImage(rgb, "rgb8"), kImage, &error), expected)) << error;
  // JPEG is lossy: within a few grey levels of the original on this smooth pattern.
  std::vector<std::uint8_t> jpeg;
  cv::imencode(".jpg", img, jpeg, {cv::IMWRITE_JPEG_QUALITY, 95});
  const cv::Mat decoded = gray(Bytes().header(kStamp).str("jpeg").data(jpeg.data(), jpeg.size()).b, kCompressedImage, &error);
  ASSERT_EQ(decoded.size(), img.size()) << error;
  cv::Mat diff;
  cv::absdiff(decoded, img, diff);
  EXPECT_LT(cv::mean(diff)[0], 3.0);
}

TEST(RosMessages, UnreadableImagesSayWhy) {
  std::string error;
  EXPECT_TRUE(gray(rawImage(pattern(4, 4), "bayer_rggb8"), kImage, &error).empty());
  EXPECT_NE(error.find("bayer_rggb8"), std::string::npos) << error;
  EXPECT_NE(error.find("mono8, mono16, bgr8 and rgb8"), std::string::npos) << error;
  // Fewer bytes than width x height says.
  std::vector<std::uint8_t> short_data = Bytes().header(kStamp).u32(100).u32(100).str("mono8").u8(0).u32(100).data("abc", 3).b;
  EXPECT_TRUE(gray(short_data, kImage, &error).empty());
  EXPECT_NE(error.find("does not hold 100x100"), std::string::npos) << error;
  // Sizes that would overflow 32 bits.
  std::vector<std::uint8_t> huge = Bytes().header(kStamp).u32(0x40000000).u32(0x40000000).str("bgr8").u8(0).u32(0xC0000000).data("a", 1).b;
  EXPECT_TRUE(gray(huge, kImage, &error).empty());
  EXPECT_TRUE(gray(Bytes().header(kStamp).str("png").data("not a png", 9).b, kCompressedImage, &error).empty());
  EXPECT_NE(error.find("does not decode"), std::string::npos) << error;
}

TEST(RosMessages, ImuRoundTripsExactlyAndRejectsNonFiniteValues) {
  imu::ImuSample s;
  s.t_ns = kStamp;
  s.gyro = Vec3(0.1, -0.2, 1.0 / 3.0);
  s.accel = Vec3(9.81, 1e-300, -2.5);
  imu::ImuSample back;
  ASSERT_TRUE(parseImu(serializeImu(s, "imu0"), &back));
  EXPECT_EQ(back.t_ns, s.t_ns);
  EXPECT_EQ(back.gyro, s.gyro);
  EXPECT_EQ(back.accel, s.accel);
  s.gyro.x() = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(parseImu(serializeImu(s, "imu0"), &back));
}

TEST(RosMessages, PoseTypesAllGiveTheBodyPose) {
  const geometry::SE3 T(geometry::SO3::exp(Vec3(0.3, -0.2, 0.1)), Vec3(1.0, 2.0, -3.0));
  const Quat q = T.quaternion();
  const auto pose = [&](Bytes b) {
    b.f64(T.translation().x()).f64(T.translation().y()).f64(T.translation().z()).f64(q.x()).f64(q.y()).f64(q.z()).f64(q.w());
    return b;
  };
  Bytes odometry = pose(Bytes().header(kStamp).str("body"));
  for (int k = 0; k < 36 + 6 + 36; ++k) odometry.f64(0.0);  // pose covariance, twist and its covariance
  const std::pair<const char*, std::vector<std::uint8_t>> cases[] = {
      {kPoseStamped, pose(Bytes().header(kStamp)).b},
      {kTransformStamped, pose(Bytes().header(kStamp).str("body")).b},
      {kOdometry, odometry.b},
      {kPoseStamped, serializePoseStamped(kStamp, "world", T)}};
  for (const auto& [type, bytes] : cases) {
    std::int64_t t = 0;
    geometry::SE3 got;
    ASSERT_TRUE(parsePose(bytes, type, &t, &got)) << type;
    EXPECT_EQ(t, kStamp);
    EXPECT_LT((got.translation() - T.translation()).norm(), 1e-15) << type;
    EXPECT_LT(geometry::angle(got.so3().inverse() * T.so3()), 1e-15) << type;
  }
  // A zero quaternion is not a rotation.
  std::int64_t t = 0;
  geometry::SE3 got;
  EXPECT_FALSE(parsePose(Bytes().header(kStamp).f64(1).f64(2).f64(3).f64(0).f64(0).f64(0).f64(0).b, kPoseStamped, &t, &got));
}

TEST(RosMessages, EveryMessageCutShortIsRejected) {
  imu::ImuSample s;
  const std::pair<const char*, std::vector<std::uint8_t>> cases[] = {
      {kImage, serializeImage(kStamp, "cam0", pattern(3, 5))},
      {kCompressedImage, serializeCompressedPng(kStamp, "cam0", pattern(3, 5))},
      {kImu, serializeImu(s, "imu0")},
      {kPoseStamped, serializePoseStamped(kStamp, "world", geometry::SE3())}};
  for (const auto& [type, bytes] : cases)
    for (std::size_t n = 0; n < bytes.size(); ++n) {
      const std::vector<std::uint8_t> cut(bytes.begin(), bytes.begin() + static_cast<long>(n));
      ImageMessage m;
      std::int64_t t = 0;
      geometry::SE3 T;
      const std::string name = type;
      const bool parsed = name == kImu ? parseImu(cut, &s) : name == kPoseStamped ? parsePose(cut, type, &t, &T) : parseImage(cut, type, &m);
      EXPECT_FALSE(parsed) << type << " cut to " << n << " of " << bytes.size() << " bytes";
    }
}

}  // namespace
}  // namespace edgevio::io::ros
