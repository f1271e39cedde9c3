#pragma once
// The IMU's data: one reading, and the sensor's noise densities.
#include <cstdint>

#include "edgevio/geometry/types.h"

namespace edgevio::imu {

/// One IMU reading in the IMU (body) frame.
struct ImuSample {
  std::int64_t t_ns = 0;
  Vec3 gyro = Vec3::Zero();   ///< angular rate ω̂ [rad/s]
  Vec3 accel = Vec3::Zero();  ///< specific force â [m/s²]
};

/// Continuous-time IMU noise densities (Kalibr/EuRoC convention), EuRoC's by default.
struct ImuNoise {
  double gyro_noise_density = 1.6968e-4;   ///< [rad/s/√Hz]
  double gyro_random_walk = 1.9393e-5;     ///< [rad/s²/√Hz]
  double accel_noise_density = 2.0e-3;     ///< [m/s²/√Hz]
  double accel_random_walk = 3.0e-3;       ///< [m/s³/√Hz]
  double rate_hz = 200.0;                  ///< nominal sample rate [Hz]
};

}  // namespace edgevio::imu
