#include "edgevio/io/ros_messages.h"

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <cstring>

#include "edgevio/io/png_reader.h"

namespace edgevio::io::ros {

namespace {

/// Reads ROS-serialised fields from a byte buffer; every read checks what is left.
class Cursor {
 public:
  explicit Cursor(const std::vector<std::uint8_t>& b) : b_(b) {}
  bool ok() const { return ok_; }
  std::uint32_t u32() {
    std::uint32_t v = 0;
    take(&v, 4);
    return v;
  }
  std::uint8_t u8() {
    std::uint8_t v = 0;
    take(&v, 1);
    return v;
  }
  double f64() {
    double v = 0;
    take(&v, 8);
    return v;
  }
  std::string string() {
    const std::uint32_t n = u32();
    if (!ok_ || n > b_.size() - i_) return fail(), std::string();
    std::string s(reinterpret_cast<const char*>(&b_[i_]), n);
    i_ += n;
    return s;
  }
  std::vector<std::uint8_t> bytes() {
    const std::uint32_t n = u32();
    if (!ok_ || n > b_.size() - i_) return fail(), std::vector<std::uint8_t>();
    std::vector<std::uint8_t> v(b_.begin() + static_cast<long>(i_), b_.begin() + static_cast<long>(i_ + n));
    i_ += n;
    return v;
  }
  void skip(std::size_t n) {
    if (n > b_.size() - i_) return fail();
    i_ += n;
  }
  /// std_msgs/Header up to its frame_id: the stamp in ns.
  std::int64_t stamp() {
    u32();  // seq
    const std::uint32_t sec = u32(), nsec = u32();
    return static_cast<std::int64_t>(sec) * 1000000000LL + nsec;
  }
  /// std_msgs/Header: the stamp in ns.
  std::int64_t header() {
    const std::int64_t t = stamp();
    string();  // frame_id
    return t;
  }
  Vec3 vec3() {
    const double x = f64(), y = f64();
    return Vec3(x, y, f64());
  }
  Quat quat() {  // x, y, z, w on the wire
    const double x = f64(), y = f64(), z = f64();
    return Quat(f64(), x, y, z);
  }

 private:
  void fail() { ok_ = false; }
  void take(void* out, std::size_t n) {  // the wire is little-endian, as every machine edgevio builds on
    if (!ok_ || n > b_.size() - i_) return fail();
    std::memcpy(out, &b_[i_], n);
    i_ += n;
  }
  const std::vector<std::uint8_t>& b_;
  std::size_t i_ = 0;
  bool ok_ = true;
};

class Writer {
 public:
  void u32(std::uint32_t v) { put(&v, 4); }
  void u8(std::uint8_t v) { put(&v, 1); }
  void f64(double v) { put(&v, 8); }
  void string(const std::string& s) {
    u32(static_cast<std::uint32_t>(s.size()));
    put(s.data(), s.size());
  }
  void bytes(const std::uint8_t* p, std::size_t n) {
    u32(static_cast<std::uint32_t>(n));
    put(p, n);
  }
  void header(std::int64_t stamp_ns, const std::string& frame_id) {
    u32(0);
    u32(static_cast<std::uint32_t>(stamp_ns / 1000000000LL));
    u32(static_cast<std::uint32_t>(stamp_ns % 1000000000LL));
    string(frame_id);
  }
  void vec3(const Vec3& v) {
    for (int k = 0; k < 3; ++k) f64(v[k]);
  }
  void quat(const Quat& q) {
    f64(q.x());
    f64(q.y());
    f64(q.z());
    f64(q.w());
  }
  void zeros(int count) {
    for (int k = 0; k < count; ++k) f64(0.0);
  }
  std::vector<std::uint8_t> take() { return std::move(b_); }

 private:
  void put(const void* p, std::size_t n) {
    const auto* c = static_cast<const std::uint8_t*>(p);
    b_.insert(b_.end(), c, c + n);
  }
  std::vector<std::uint8_t> b_;
};

geometry::SE3 pose(const Vec3& p, const Quat& q) { return geometry::SE3(q.normalized(), p); }

}  // namespace

bool parseImage(const std::vector<std::uint8_t>& bytes, const std::string& type, ImageMessage* out) {
  Cursor c(bytes);
  out->stamp_ns = c.header();
  out->compressed = type == kCompressedImage;
  if (out->compressed) {
    out->encoding = c.string();
  } else {
    out->height = c.u32();
    out->width = c.u32();
    out->encoding = c.string();
    out->big_endian = c.u8() != 0;
    out->step = c.u32();
  }
  out->data = c.bytes();
  return c.ok();
}

namespace {
// Larger than any camera's side; beyond it a header is damaged, and the
// sizes would not fit OpenCV's int.
constexpr std::uint32_t kMaxImageSide = 1u << 15;
}  // namespace

cv::Mat toGray(const ImageMessage& m, std::string* error) {
  if (m.compressed) {
    cv::Mat gray = decodePngGray8(m.data);  // the folder reader's fast path; exactly what OpenCV gives
    try {
      if (gray.empty()) gray = cv::imdecode(m.data, cv::IMREAD_GRAYSCALE);
    } catch (const cv::Exception&) {
    }
    if (gray.empty()) *error = "a compressed image (format '" + m.encoding + "') that does not decode as PNG or JPEG";
    return gray;
  }
  const auto rows = static_cast<int>(m.height), cols = static_cast<int>(m.width);
  int bytes_per_pixel = 0, channels = 1;
  if (m.encoding == "mono8" || m.encoding == "8UC1") bytes_per_pixel = 1;
  if (m.encoding == "mono16" || m.encoding == "16UC1") bytes_per_pixel = 2;
  if (m.encoding == "bgr8" || m.encoding == "rgb8") bytes_per_pixel = channels = 3;
  if (bytes_per_pixel == 0) {
    *error = "encoding '" + m.encoding + "' (edgevio reads mono8, mono16, bgr8 and rgb8)";
    return {};
  }
  // In 64 bits: width, height and step are whatever the message says.
  const std::uint64_t row_bytes = std::uint64_t{m.width} * static_cast<std::uint64_t>(bytes_per_pixel);
  if (m.width == 0 || m.height == 0 || m.width > kMaxImageSide || m.height > kMaxImageSide || m.step < row_bytes ||
      m.data.size() < std::uint64_t{m.step} * m.height) {
    *error = "an image whose data (" + std::to_string(m.data.size()) + " bytes) does not hold " + std::to_string(cols) + "x" +
             std::to_string(rows) + " pixels of " + m.encoding;
    return {};
  }
  const int type = bytes_per_pixel == 2 ? CV_16UC1 : CV_8UC(channels);
  const cv::Mat wrapped(rows, cols, type, const_cast<std::uint8_t*>(m.data.data()), m.step);
  cv::Mat gray;
  if (bytes_per_pixel == 2) {  // the upper byte, as OpenCV reads a 16-bit PNG as grey
    gray.create(rows, cols, CV_8UC1);
    const int upper = m.big_endian ? 0 : 1;  // the upper byte's place in each pixel's two
    for (int v = 0; v < rows; ++v) {
      const std::uint8_t* row = m.data.data() + static_cast<std::size_t>(v) * m.step;
      for (int u = 0; u < cols; ++u) gray.at<std::uint8_t>(v, u) = row[2 * u + upper];
    }
  } else if (channels == 3) {
    cv::cvtColor(wrapped, gray, m.encoding == "rgb8" ? cv::COLOR_RGB2GRAY : cv::COLOR_BGR2GRAY);
  } else {
    gray = wrapped.clone();
  }
  return gray;
}

bool parseImu(const std::vector<std::uint8_t>& bytes, imu::ImuSample* out) {
  Cursor c(bytes);
  out->t_ns = c.header();
  c.skip(4 * 8 + 9 * 8);  // orientation and its covariance
  out->gyro = c.vec3();
  c.skip(9 * 8);
  out->accel = c.vec3();
  c.skip(9 * 8);
  return c.ok() && out->gyro.allFinite() && out->accel.allFinite();
}

bool parseHeaderStamp(const std::vector<std::uint8_t>& bytes, std::int64_t* stamp_ns) {
  Cursor c(bytes);
  *stamp_ns = c.stamp();
  return c.ok();
}

bool parsePose(const std::vector<std::uint8_t>& bytes, const std::string& type, std::int64_t* stamp_ns, geometry::SE3* T) {
  Cursor c(bytes);
  *stamp_ns = c.header();
  if (type == kTransformStamped || type == kOdometry) c.string();  // child_frame_id
  const Vec3 p = c.vec3();
  const Quat q = c.quat();
  if (!c.ok() || !p.allFinite() || !q.coeffs().allFinite() || q.norm() < 0.5) return false;
  *T = pose(p, q);
  return true;
}

std::vector<std::uint8_t> serializeImage(std::int64_t stamp_ns, const std::string& frame_id, const cv::Mat& gray8) {
  Writer w;
  w.header(stamp_ns, frame_id);
  w.u32(static_cast<std::uint32_t>(gray8.rows));
  w.u32(static_cast<std::uint32_t>(gray8.cols));
  w.string("mono8");
  w.u8(0);
  w.u32(static_cast<std::uint32_t>(gray8.cols));
  const cv::Mat packed = gray8.isContinuous() ? gray8 : gray8.clone();
  w.bytes(packed.data, packed.total());
  return w.take();
}

std::vector<std::uint8_t> serializeCompressedPng(std::int64_t stamp_ns, const std::string& frame_id, const cv::Mat& gray8) {
  std::vector<std::uint8_t> png;
  cv::imencode(".png", gray8, png);
  Writer w;
  w.header(stamp_ns, frame_id);
  w.string("png");
  w.bytes(png.data(), png.size());
  return w.take();
}

std::vector<std::uint8_t> serializeImu(const imu::ImuSample& s, const std::string& frame_id) {
  Writer w;
  w.header(s.t_ns, frame_id);
  w.quat(Quat::Identity());
  w.f64(-1.0);  // orientation_covariance[0] = -1: no orientation estimate (sensor_msgs/Imu's convention)
  w.zeros(8);
  w.vec3(s.gyro);
  w.zeros(9);
  w.vec3(s.accel);
  w.zeros(9);
  return w.take();
}

std::vector<std::uint8_t> serializePoseStamped(std::int64_t stamp_ns, const std::string& frame_id, const geometry::SE3& T) {
  Writer w;
  w.header(stamp_ns, frame_id);
  w.vec3(T.translation());
  w.quat(T.quaternion());
  return w.take();
}

namespace {
constexpr char kSeparator[] = "\n================================================================================\n";
constexpr char kHeaderDef[] = "MSG: std_msgs/Header\nuint32 seq\ntime stamp\nstring frame_id\n";
constexpr char kQuaternionDef[] = "MSG: geometry_msgs/Quaternion\nfloat64 x\nfloat64 y\nfloat64 z\nfloat64 w\n";
}  // namespace

const MessageType& messageType(const std::string& name) {
  static const std::string image = std::string(
      "Header header\nuint32 height\nuint32 width\nstring encoding\nuint8 is_bigendian\nuint32 step\nuint8[] data\n") + kSeparator + kHeaderDef;
  static const std::string compressed = std::string("Header header\nstring format\nuint8[] data\n") + kSeparator + kHeaderDef;
  static const std::string imu = std::string(
      "Header header\ngeometry_msgs/Quaternion orientation\nfloat64[9] orientation_covariance\n"
      "geometry_msgs/Vector3 angular_velocity\nfloat64[9] angular_velocity_covariance\n"
      "geometry_msgs/Vector3 linear_acceleration\nfloat64[9] linear_acceleration_covariance\n") +
      kSeparator + kHeaderDef + kSeparator + kQuaternionDef + kSeparator + "MSG: geometry_msgs/Vector3\nfloat64 x\nfloat64 y\nfloat64 z\n";
  static const std::string pose = std::string("Header header\ngeometry_msgs/Pose pose\n") + kSeparator + kHeaderDef + kSeparator +
                                  "MSG: geometry_msgs/Pose\ngeometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n" +
                                  kSeparator + "MSG: geometry_msgs/Point\nfloat64 x\nfloat64 y\nfloat64 z\n" + kSeparator + kQuaternionDef;
  static const MessageType types[] = {{kImage, "060021388200f6f0f447d0fcd9c64743", image.c_str()},
                                      {kCompressedImage, "8f7a12909da2c9d3332d540a0977563f", compressed.c_str()},
                                      {kImu, "6a62c6daae103f4ff57a132d6f95cec2", imu.c_str()},
                                      {kPoseStamped, "d3812c3cbc69362b77dc0b19b345f8f5", pose.c_str()}};
  for (const MessageType& t : types)
    if (name == t.name) return t;
  static const MessageType unknown{"", "*", ""};
  return unknown;
}

}  // namespace edgevio::io::ros
