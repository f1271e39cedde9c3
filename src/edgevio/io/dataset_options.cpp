#include "edgevio/io/dataset_options.h"

namespace edgevio::io {

std::string DatasetOptions::validate() const {
  if (!(stereo_sync_tolerance_s >= 0.0 && stereo_sync_tolerance_s < 0.5))
    return "stereo_sync_tolerance_s: must be in [0, 0.5)";
  if (!(imu_gap_warning_s > 0.0)) return "imu_gap_warning_s: must be > 0";
  return {};
}

}  // namespace edgevio::io
