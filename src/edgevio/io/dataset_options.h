#pragma once
#include <string>

namespace edgevio::io {

/// Options of the EuRoC/ASL dataset reader (config section `dataset`).
struct DatasetOptions {
  /// Largest |t_cam0 − t_cam1| for two images to form a stereo pair. [s]
  double stereo_sync_tolerance_s = 0.003;
  /// An IMU gap longer than this is reported as a warning. [s]
  double imu_gap_warning_s = 0.025;

  template <class Visitor>
  void visit(Visitor& v) {
    v("stereo_sync_tolerance_s", stereo_sync_tolerance_s, "s",
      "largest |t_cam0 - t_cam1| for two images to form a stereo pair");
    v("imu_gap_warning_s", imu_gap_warning_s, "s", "an IMU gap longer than this is reported as a warning");
  }
  /// Empty when valid, else what is wrong.
  std::string validate() const;
};

}  // namespace edgevio::io
