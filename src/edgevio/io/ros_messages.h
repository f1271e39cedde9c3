#pragma once
// The few ROS 1 messages a VIO dataset carries, (de)serialised as ROS 1
// does: little-endian fields in declaration order, strings and arrays as a
// u32 length then their bytes, fixed arrays without a length.
//   std_msgs/Header                seq u32, stamp (sec u32, nsec u32), frame_id string
//   sensor_msgs/Image              Header, height u32, width u32, encoding string,
//                                  is_bigendian u8, step u32, data u8[]
//   sensor_msgs/CompressedImage    Header, format string, data u8[]
//   sensor_msgs/Imu                Header, orientation (x, y, z, w f64), f64[9],
//                                  angular_velocity (3 f64), f64[9], linear_acceleration (3 f64), f64[9]
//   geometry_msgs/PoseStamped      Header, position (3 f64), orientation (x, y, z, w f64)
//   geometry_msgs/TransformStamped Header, child_frame_id string, translation (3 f64), rotation (x, y, z, w f64)
//   nav_msgs/Odometry              Header, child_frame_id string, pose (position, orientation), f64[36], twist ...
// A message whose bytes end early is an error (false), never a read past them.
#include <opencv2/core.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "edgevio/geometry/se3.h"
#include "edgevio/imu/imu_types.h"

namespace edgevio::io::ros {

inline constexpr char kImage[] = "sensor_msgs/Image";
inline constexpr char kCompressedImage[] = "sensor_msgs/CompressedImage";
inline constexpr char kImu[] = "sensor_msgs/Imu";
inline constexpr char kPoseStamped[] = "geometry_msgs/PoseStamped";
inline constexpr char kTransformStamped[] = "geometry_msgs/TransformStamped";
inline constexpr char kOdometry[] = "nav_msgs/Odometry";

/// An image message before decoding: raw pixels (Image) or a PNG/JPEG file (CompressedImage).
struct ImageMessage {
  std::int64_t stamp_ns = 0;
  bool compressed = false;
  std::string encoding;  ///< Image: mono8, mono16, bgr8, rgb8, ...; CompressedImage: its format ("png", "jpeg", ...)
  std::uint32_t width = 0, height = 0, step = 0;
  bool big_endian = false;
  std::vector<std::uint8_t> data;
};

/// Parses an Image or CompressedImage (by `type`); false when the bytes are too few.
bool parseImage(const std::vector<std::uint8_t>& bytes, const std::string& type, ImageMessage* out);
/// The image as 8-bit grey; empty with `error` set for an encoding edgevio does not read.
cv::Mat toGray(const ImageMessage& m, std::string* error);

/// A std_msgs/Header's seq and stamp: the first bytes of every message above.
inline constexpr std::size_t kHeaderStampBytes = 12;
/// The stamp of a message that starts with a Header, from at least its first
/// kHeaderStampBytes bytes; false when there are fewer.
bool parseHeaderStamp(const std::vector<std::uint8_t>& bytes, std::int64_t* stamp_ns);

bool parseImu(const std::vector<std::uint8_t>& bytes, imu::ImuSample* out);
/// A PoseStamped, TransformStamped or Odometry (by `type`) as a timestamped pose.
bool parsePose(const std::vector<std::uint8_t>& bytes, const std::string& type, std::int64_t* stamp_ns, geometry::SE3* T);

std::vector<std::uint8_t> serializeImage(std::int64_t stamp_ns, const std::string& frame_id, const cv::Mat& gray8);
std::vector<std::uint8_t> serializeCompressedPng(std::int64_t stamp_ns, const std::string& frame_id, const cv::Mat& gray8);
std::vector<std::uint8_t> serializeImu(const imu::ImuSample& s, const std::string& frame_id);
std::vector<std::uint8_t> serializePoseStamped(std::int64_t stamp_ns, const std::string& frame_id, const geometry::SE3& T);

/// The md5sum and full definition ROS records with each connection of a type.
struct MessageType {
  const char* name;
  const char* md5sum;
  const char* definition;
};
const MessageType& messageType(const std::string& name);

}  // namespace edgevio::io::ros
