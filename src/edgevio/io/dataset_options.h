#pragma once
#include "edgevio/common/options.h"

namespace edgevio::io {

/// Reading a dataset (config section `dataset`).
struct DatasetOptions {
  double stereo_sync_tolerance_s, imu_gap_warning_s;

  EDGEVIO_OPTIONS(DatasetOptions)
};

EDGEVIO_OPTIONS_TABLE(DatasetOptions,
    number("stereo_sync_tolerance_s", &S::stereo_sync_tolerance_s, 0.003, "s",
           "largest |t_cam0 - t_cam1| for two images to form a stereo pair", halfOpen(0, 0.5)),
    number("imu_gap_warning_s", &S::imu_gap_warning_s, 0.025, "s", "an IMU gap longer than this is reported as a warning",
           above(0)))

}  // namespace edgevio::io
