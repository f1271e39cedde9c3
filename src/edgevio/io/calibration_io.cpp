#include "edgevio/io/calibration_io.h"

#include <filesystem>

#include "edgevio/common/error.h"
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

void readImuNoise(const YAML::Node& node, const std::string& path, camera::ImuNoise* imu) {
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
  }
  if (!imu_yaml.empty()) {
    const YAML::Node imu_root = loadYamlFile(imu_yaml);
    const YAML::Node imu = yamlRequire(imu_root, "imu0", imu_yaml);
    readImuNoise(imu, imu_yaml, &rig.imu);
    rig.imu.rate_hz = yamlDouble(imu, "update_rate", imu_yaml);
  }
  return rig;
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
