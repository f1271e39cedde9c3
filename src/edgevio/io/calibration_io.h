#pragma once
// Reading rig calibrations: EuRoC ASL (`mav0/{cam0,cam1,imu0}/sensor.yaml`) and
// Kalibr (`camchain-imucam.yaml`, optionally `imu.yaml` beside it).
#include <string>

#include "edgevio/camera/calibration.h"

namespace edgevio::io {

/// Reads cam0, cam1 and imu0 sensor.yaml files of an ASL `mav0` folder.
camera::StereoRig loadEurocCalibration(const std::string& mav0_dir);

/// Reads a Kalibr camchain-imucam.yaml; IMU noise from imu_yaml when non-empty.
camera::StereoRig loadKalibrCalibration(const std::string& camchain_yaml, const std::string& imu_yaml = "");

/// A dataset folder (containing mav0/ or being it) → EuRoC; a YAML file → Kalibr
/// (with an imu.yaml next to it when there is one).
camera::StereoRig loadCalibration(const std::string& path);

/// Writes mav0/{cam0,cam1,imu0}/sensor.yaml in the EuRoC format (folders are created).
void writeEurocCalibration(const std::string& mav0_dir, const camera::StereoRig& rig);

/// Writes a Kalibr camchain-imucam.yaml and imu.yaml (with the rig's topics).
void writeKalibrCalibration(const std::string& camchain_yaml, const std::string& imu_yaml, const camera::StereoRig& rig);

/// The EuRoC MAV rig (V1_01 calibration), the simulator's default.
camera::StereoRig eurocDefaultRig();

/// Reads one EuRoC camera sensor.yaml.
void loadEurocCamera(const std::string& path, camera::CameraModel* model, geometry::SE3* T_b_c, double* rate_hz);

}  // namespace edgevio::io
