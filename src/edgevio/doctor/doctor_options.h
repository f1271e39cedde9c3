#pragma once
#include "edgevio/common/options.h"

namespace edgevio::doctor {

/// `edgevio doctor` (config section `doctor`): how much of a sequence it
/// reads, and the thresholds beyond which a measurement becomes a finding.
struct DoctorOptions {
  double max_duration_s, max_time_offset_ms, min_rotation_rate_rad_s, standstill_min_s, standstill_gyro_std_rad_s,
      standstill_accel_std_mps2, time_offset_warning_ms, rotation_warning_deg, vertical_disparity_warning_px,
      noise_ratio_warning, gravity_tolerance_mps2, valid_depth_warning, exposure_jump, blur_ratio, clipped_pixels,
      clipped_frames_warning, min_imu_rate_hz;
  int stereo_frames;

  EDGEVIO_OPTIONS(DoctorOptions)
};

// DoctorOptions's keys, defaults, units, meanings and valid values: its table in doctor_options.cpp.

}  // namespace edgevio::doctor
