#pragma once
#include "edgevio/common/options.h"

namespace edgevio::io {

/// Reading a dataset (config section `dataset`).
struct DatasetOptions {
  double stereo_sync_tolerance_s, imu_gap_warning_s, imu_glitch_gyro_rad_s, imu_glitch_accel_mps2, imu_time_offset_ms;

  EDGEVIO_OPTIONS(DatasetOptions)
};

// DatasetOptions's keys, defaults, units, meanings and valid values: its table in dataset_options.cpp.

}  // namespace edgevio::io
