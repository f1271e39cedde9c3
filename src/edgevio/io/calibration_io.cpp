#include "edgevio/io/calibration_io.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/yaml_file.h"

namespace edgevio::io {

namespace fs = std::filesystem;
using camera::CameraModel;
using camera::StereoRig;

namespace {

void readIntrinsics(const YAML::Node& node, const std::string& path, const char* distortion_key,
                    const char* coeffs_key, CameraModel* m) {
  const std::string model = yamlString(node, "camera_model", path);
  if (model != "pinhole")
    throw InputError(path, yamlLine(node["camera_model"]),
                     "camera_model '" + model + "' is not supported (expected 'pinhole')");
  const std::vector<double> res = yamlDoubles(node, "resolution", path, 2);
  const std::vector<double> k = yamlDoubles(node, "intrinsics", path, 4);
  for (double pixels : res)
    if (pixels < 1 || pixels > 65535 || pixels != std::floor(pixels))
      throw InputError(path, yamlLine(node["resolution"]), "resolution: [width, height] in whole pixels, 1 to 65535 each");
  m->width = static_cast<int>(res[0]);
  m->height = static_cast<int>(res[1]);
  m->fx = k[0];
  m->fy = k[1];
  m->cx = k[2];
  m->cy = k[3];
  const std::string dist = yamlString(node, distortion_key, path);
  if (!camera::parseDistortion(dist, &m->distortion))
    throw InputError(path, yamlLine(node[distortion_key]),
                     std::string(distortion_key) + " '" + dist +
                         "' is not supported (expected radial-tangential/radtan, equidistant or none)");
  if (m->distortion != camera::Distortion::kNone) {
    const std::vector<double> d = yamlDoubles(node, coeffs_key, path, 4);
    for (std::size_t i = 0; i < 4; ++i) m->coeffs[i] = d[i];
  }
  const std::string err = m->validate();
  if (!err.empty()) throw InputError(path, yamlLine(node), "invalid camera: " + err);
}

void readImuNoise(const YAML::Node& node, const std::string& path, imu::ImuNoise* imu) {
  imu->gyro_noise_density = yamlDouble(node, "gyroscope_noise_density", path);
  imu->gyro_random_walk = yamlDouble(node, "gyroscope_random_walk", path);
  imu->accel_noise_density = yamlDouble(node, "accelerometer_noise_density", path);
  imu->accel_random_walk = yamlDouble(node, "accelerometer_random_walk", path);
  if (!(imu->gyro_noise_density > 0 && imu->gyro_random_walk > 0 && imu->accel_noise_density > 0 &&
        imu->accel_random_walk > 0))
    throw InputError(path, yamlLine(node), "IMU noise densities must all be > 0");
}

}  // namespace

void loadEurocCamera(const std::string& path, CameraModel* model, geometry::SE3* T_b_c, double* rate_hz) {
  const YAML::Node root = loadYamlFile(path);
  readIntrinsics(root, path, "distortion_model", "distortion_coefficients", model);
  *T_b_c = geometry::SE3::fromMatrix(yamlMatrix4(root, "T_BS", path));
  *rate_hz = yamlDouble(root, "rate_hz", path);
  if (!(*rate_hz > 0.0)) throw InputError(path, yamlLine(root["rate_hz"]), "rate_hz must be > 0");
}

StereoRig loadEurocCalibration(const std::string& mav0_dir) {
  StereoRig rig;
  for (int i = 0; i < 2; ++i)
    loadEurocCamera((fs::path(mav0_dir) / ("cam" + std::to_string(i)) / "sensor.yaml").string(), &rig.cam[i],
                    &rig.T_b_c[i], &rig.camera_rate_hz);
  const std::string imu_path = (fs::path(mav0_dir) / "imu0" / "sensor.yaml").string();
  const YAML::Node imu = loadYamlFile(imu_path);
  readImuNoise(imu, imu_path, &rig.imu);
  rig.imu.rate_hz = yamlDouble(imu, "rate_hz", imu_path);
  // Poses are of the IMU frame, so any T_BS of the IMU other than identity
  // would mean a body frame we do not model.
  const geometry::SE3 T_b_i = geometry::SE3::fromMatrix(yamlMatrix4(imu, "T_BS", imu_path));
  if (T_b_i.log().norm() > 1e-6)
    throw InputError(imu_path, yamlLine(imu["T_BS"]),
                     "imu0 T_BS must be the identity (edgevio's body frame is the IMU frame)");
  return rig;
}

StereoRig loadKalibrCalibration(const std::string& camchain_yaml, const std::string& imu_yaml) {
  const YAML::Node root = loadYamlFile(camchain_yaml);
  StereoRig rig;
  for (int i = 0; i < 2; ++i) {
    const YAML::Node cam = yamlRequire(root, "cam" + std::to_string(i), camchain_yaml);
    readIntrinsics(cam, camchain_yaml, "distortion_model", "distortion_coeffs", &rig.cam[i]);
    rig.T_b_c[i] = geometry::SE3::fromMatrix(yamlMatrix4(cam, "T_cam_imu", camchain_yaml)).inverse();
    if (cam["rostopic"] && cam["rostopic"].IsScalar()) rig.topic[i] = cam["rostopic"].Scalar();
  }
  double timeshift[2] = {0.0, 0.0};
  bool has_timeshift[2] = {false, false};
  for (int i = 0; i < 2; ++i) {
    const std::string cam = "cam" + std::to_string(i);
    if (!root[cam]["timeshift_cam_imu"]) continue;
    has_timeshift[i] = true;
    timeshift[i] = yamlDouble(root[cam], "timeshift_cam_imu", camchain_yaml);
    if (!std::isfinite(timeshift[i]) || std::abs(timeshift[i]) > 1.0)
      throw InputError(camchain_yaml, yamlLine(root[cam]["timeshift_cam_imu"]),
                       cam + " timeshift_cam_imu must be a time in seconds within +-1 s (t_imu = t_cam + shift)");
  }
  rig.imu_time_offset_s = timeshift[0];
  // edgevio takes a stereo pair as taken at once, on cam0's clock. A right
  // image 1 ms off moves the baseline by 1 mm per m/s of motion across it:
  // about 1 % of an 11 cm baseline's depth at 1 m/s. (Kalibr writes a shift
  // for every camera; a file with one only says nothing of the other.)
  constexpr double kStereoSkewWarningS = 1e-3;
  if (has_timeshift[0] && has_timeshift[1] && std::abs(timeshift[1] - timeshift[0]) > kStereoSkewWarningS) {
    rig.warnings.push_back(formatText("%s:%zu: cam1's timeshift_cam_imu differs from cam0's by %.1f ms; edgevio takes both "
                                      "images at cam0's, so stereo depth is off while the rig moves: synchronise the "
                                      "cameras' triggers (or recalibrate, if they are)",
                                      camchain_yaml.c_str(), yamlLine(root["cam1"]["timeshift_cam_imu"]),
                                      1e3 * (timeshift[1] - timeshift[0])));
  }
  if (!imu_yaml.empty()) {
    const YAML::Node imu_root = loadYamlFile(imu_yaml);
    const YAML::Node imu = yamlRequire(imu_root, "imu0", imu_yaml);
    readImuNoise(imu, imu_yaml, &rig.imu);
    rig.imu.rate_hz = yamlDouble(imu, "update_rate", imu_yaml);
    if (imu["rostopic"] && imu["rostopic"].IsScalar()) rig.imu_topic = imu["rostopic"].Scalar();
  }
  return rig;
}

void writeEurocCalibration(const std::string& mav0_dir, const StereoRig& rig) {
  for (int i = 0; i < 2; ++i) {
    const fs::path dir = fs::path(mav0_dir) / ("cam" + std::to_string(i));
    fs::create_directories(dir);
    std::ofstream f(dir / "sensor.yaml");
    if (!f) throw InputError((dir / "sensor.yaml").string(), 0, "cannot write calibration file");
    const CameraModel& c = rig.cam[i];
    const Mat4 T = rig.T_b_c[i].matrix();
    f << std::setprecision(17) << "%YAML:1.0\n# General sensor definitions.\nsensor_type: camera\ncomment: edgevio cam" << i
      << "\n\n# Sensor extrinsics wrt. the body-frame.\nT_BS:\n  cols: 4\n  rows: 4\n  data: [";
    for (int k = 0; k < 16; ++k) f << T(k / 4, k % 4) << (k < 15 ? (k % 4 == 3 ? ",\n         " : ", ") : "]\n");
    f << "\n# Camera specific definitions.\nrate_hz: " << rig.camera_rate_hz << "\nresolution: [" << c.width << ", "
      << c.height << "]\ncamera_model: pinhole\nintrinsics: [" << c.fx << ", " << c.fy << ", " << c.cx << ", " << c.cy
      << "] #fu, fv, cu, cv\ndistortion_model: " << camera::distortionName(c.distortion)
      << "\ndistortion_coefficients: [" << c.coeffs[0] << ", " << c.coeffs[1] << ", " << c.coeffs[2] << ", "
      << c.coeffs[3] << "]\n";
  }
  const fs::path dir = fs::path(mav0_dir) / "imu0";
  fs::create_directories(dir);
  std::ofstream f(dir / "sensor.yaml");
  if (!f) throw InputError((dir / "sensor.yaml").string(), 0, "cannot write calibration file");
  f << std::setprecision(17) << "%YAML:1.0\nsensor_type: imu\ncomment: edgevio IMU\n\nT_BS:\n  cols: 4\n  rows: 4\n"
    << "  data: [1.0, 0.0, 0.0, 0.0,\n         0.0, 1.0, 0.0, 0.0,\n         0.0, 0.0, 1.0, 0.0,\n         0.0, 0.0, 0.0, 1.0]\n"
    << "rate_hz: " << rig.imu.rate_hz << "\n\n"
    << "gyroscope_noise_density: " << rig.imu.gyro_noise_density << "     # [ rad / s / sqrt(Hz) ]\n"
    << "gyroscope_random_walk: " << rig.imu.gyro_random_walk << "       # [ rad / s^2 / sqrt(Hz) ]\n"
    << "accelerometer_noise_density: " << rig.imu.accel_noise_density << "  # [ m / s^2 / sqrt(Hz) ]\n"
    << "accelerometer_random_walk: " << rig.imu.accel_random_walk << "    # [ m / s^3 / sqrt(Hz) ]\n";
}

void writeKalibrCalibration(const std::string& camchain_yaml, const std::string& imu_yaml, const StereoRig& rig) {
  std::ofstream f(camchain_yaml);
  if (!f) throw InputError(camchain_yaml, 0, "cannot write calibration file");
  f << std::setprecision(17);
  for (int i = 0; i < 2; ++i) {
    const CameraModel& c = rig.cam[i];
    const Mat4 T = rig.T_b_c[i].inverse().matrix();
    const char* distortion = c.distortion == camera::Distortion::kEquidistant ? "equidistant"
                             : c.distortion == camera::Distortion::kNone      ? "none"
                                                                              : "radtan";
    f << "cam" << i << ":\n  camera_model: pinhole\n  intrinsics: [" << c.fx << ", " << c.fy << ", " << c.cx << ", " << c.cy
      << "]\n  distortion_model: " << distortion << "\n  distortion_coeffs: [" << c.coeffs[0] << ", " << c.coeffs[1] << ", "
      << c.coeffs[2] << ", " << c.coeffs[3] << "]\n  resolution: [" << c.width << ", " << c.height << "]\n  rostopic: '"
      << rig.topic[i] << "'\n  T_cam_imu:\n";
    for (int r = 0; r < 4; ++r) f << "  - [" << T(r, 0) << ", " << T(r, 1) << ", " << T(r, 2) << ", " << T(r, 3) << "]\n";
    f << "  timeshift_cam_imu: " << rig.imu_time_offset_s << "\n";
  }
  std::ofstream g(imu_yaml);
  if (!g) throw InputError(imu_yaml, 0, "cannot write calibration file");
  g << std::setprecision(17) << "imu0:\n  accelerometer_noise_density: " << rig.imu.accel_noise_density
    << "\n  accelerometer_random_walk: " << rig.imu.accel_random_walk << "\n  gyroscope_noise_density: " << rig.imu.gyro_noise_density
    << "\n  gyroscope_random_walk: " << rig.imu.gyro_random_walk << "\n  rostopic: '" << rig.imu_topic
    << "'\n  update_rate: " << rig.imu.rate_hz << "\n";
}

StereoRig eurocDefaultRig() {
  StereoRig rig;
  const double T0[16] = {0.0148655429818, -0.999880929698, 0.00414029679422, -0.0216401454975,
                         0.999557249008,  0.0149672133247, 0.025715529948,   -0.064676986768,
                         -0.0257744366974, 0.00375618835797, 0.999660727178, 0.00981073058949,
                         0.0, 0.0, 0.0, 1.0};
  const double T1[16] = {0.0125552670891, -0.999755099723, 0.0182237714554, -0.0198435579556,
                         0.999598781151,  0.0130119051815, 0.0251588363115, 0.0453689425024,
                         -0.0253898008918, 0.0179005838253, 0.999517347078, 0.00786212447038,
                         0.0, 0.0, 0.0, 1.0};
  rig.T_b_c[0] = geometry::SE3::fromMatrix(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(T0));
  rig.T_b_c[1] = geometry::SE3::fromMatrix(Eigen::Map<const Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(T1));
  const double intr[2][4] = {{458.654, 457.296, 367.215, 248.375}, {457.587, 456.134, 379.999, 255.238}};
  const std::array<double, 4> dist[2] = {{-0.28340811, 0.07395907, 0.00019359, 1.76187114e-05},
                                         {-0.28368365, 0.07451284, -0.00010473, -3.55590700e-05}};
  for (int i = 0; i < 2; ++i) {
    CameraModel& c = rig.cam[i];
    c.width = 752;
    c.height = 480;
    c.fx = intr[i][0];
    c.fy = intr[i][1];
    c.cx = intr[i][2];
    c.cy = intr[i][3];
    c.distortion = camera::Distortion::kRadialTangential;
    c.coeffs = dist[i];
  }
  rig.camera_rate_hz = 20.0;
  return rig;  // ImuNoise defaults are the EuRoC ADIS16448 densities
}

StereoRig loadCalibration(const std::string& path) {
  const fs::path p(path);
  if (fs::is_directory(p)) {
    if (fs::is_directory(p / "mav0")) return loadEurocCalibration((p / "mav0").string());
    return loadEurocCalibration(p.string());
  }
  const fs::path imu = p.parent_path() / "imu.yaml";
  return loadKalibrCalibration(path, fs::exists(imu) ? imu.string() : "");
}

}  // namespace edgevio::io
