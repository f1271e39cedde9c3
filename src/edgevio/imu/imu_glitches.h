#pragma once
// IMU glitches: single readings far from their neighbours (a bus error, an
// electrical spike), which preintegration would turn into a velocity error
// for the rest of the window. A real motion cannot change the gyroscope or
// the accelerometer by much within two readings; a reading that stands out
// from the median of the five around it by more than that is replaced by
// the median.
#include <cstddef>
#include <vector>

#include "edgevio/imu/imu_types.h"

namespace edgevio::imu {

/// Replaces every reading whose gyroscope (any axis) differs from the median
/// of readings i-2..i+2 by more than max_gyro_jump_rad_s, or whose
/// accelerometer by more than max_accel_jump_mps2, with that median (0: that
/// test off). Readings next to a gap (the five span more than six typical
/// periods) are left alone. Returns the indices replaced.
std::vector<std::size_t> replaceGlitches(std::vector<ImuSample>* imu, double max_gyro_jump_rad_s, double max_accel_jump_mps2);

}  // namespace edgevio::imu
