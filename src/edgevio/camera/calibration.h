#pragma once
// Calibration of a stereo camera + IMU rig (METHOD.md §2). Frames: B = body =
// IMU; C0, C1 = left and right camera. T_b_c maps camera points into the body
// frame (EuRoC sensor.yaml calls it T_BS; Kalibr gives its inverse T_cam_imu).
#include "edgevio/camera/camera_model.h"
#include "edgevio/geometry/se3.h"

namespace edgevio::camera {

/// Continuous-time IMU noise densities (Kalibr/EuRoC convention).
struct ImuNoise {
  double gyro_noise_density = 1.6968e-4;   ///< [rad/s/√Hz]
  double gyro_random_walk = 1.9393e-5;     ///< [rad/s²/√Hz]
  double accel_noise_density = 2.0e-3;     ///< [m/s²/√Hz]
  double accel_random_walk = 3.0e-3;       ///< [m/s³/√Hz]
  double rate_hz = 200.0;                  ///< nominal sample rate [Hz]
};

struct StereoRig {
  CameraModel cam[2];
  geometry::SE3 T_b_c[2];
  double camera_rate_hz = 20.0;  ///< nominal frame rate [Hz]
  ImuNoise imu;

  /// Pose of the right camera in the left camera's frame.
  geometry::SE3 T_c0_c1() const { return T_b_c[0].inverse() * T_b_c[1]; }
};

}  // namespace edgevio::camera
