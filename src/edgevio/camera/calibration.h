#pragma once
// Calibration of a stereo camera + IMU rig (METHOD.md §2). Frames: B = body =
// IMU; C0, C1 = left and right camera. T_b_c maps camera points into the body
// frame (EuRoC sensor.yaml calls it T_BS; Kalibr gives its inverse T_cam_imu).
#include <string>
#include <vector>

#include "edgevio/camera/camera_model.h"
#include "edgevio/geometry/se3.h"
#include "edgevio/imu/imu_types.h"

namespace edgevio::camera {

struct StereoRig {
  CameraModel cam[2];
  geometry::SE3 T_b_c[2];
  double camera_rate_hz = 20.0;  ///< nominal frame rate [Hz]
  imu::ImuNoise imu;
  /// The IMU's clock minus the cameras' [s]: Kalibr's timeshift_cam_imu of
  /// cam0 (t_imu = t_cam + shift); 0 for EuRoC's sensor.yaml files, which have none.
  double imu_time_offset_s = 0.0;
  /// The ROS topics the calibration was made from (Kalibr's rostopic), or empty.
  std::string topic[2], imu_topic;
  /// What reading the calibration noticed that the run should report.
  std::vector<std::string> warnings;

  /// Pose of the right camera in the left camera's frame.
  geometry::SE3 T_c0_c1() const { return T_b_c[0].inverse() * T_b_c[1]; }
};

}  // namespace edgevio::camera
