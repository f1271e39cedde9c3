#pragma once
// The one reader (and writer) of EuRoC IMU CSV files:
// `timestamp [ns],w_x,w_y,w_z [rad/s],a_x,a_y,a_z [m/s²]`.
#include <string>
#include <vector>

#include "edgevio/imu/imu_types.h"

namespace edgevio::io {

/// Reads every row. Malformed rows, NaN/inf and duplicate or decreasing
/// timestamps are InputError (file and line); gaps longer than gap_warning_s
/// are appended to `warnings`.
std::vector<imu::ImuSample> readImuCsv(const std::string& path, double gap_warning_s, std::vector<std::string>* warnings);

void writeImuCsv(const std::string& path, const std::vector<imu::ImuSample>& samples);

}  // namespace edgevio::io
