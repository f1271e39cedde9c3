#pragma once
// Writes small EuRoC ASL folders for reader tests: a few 64x48 stereo frames,
// 200 Hz IMU, ground truth, calibration files. Each test then breaks one thing.
#include <cstdint>
#include <string>

#include "common/test_support.h"

namespace edgevio::test {

struct MiniDatasetSpec {
  int frames = 5;
  int width = 64, height = 48;
  std::int64_t t0_ns = 1000000000;
  std::int64_t frame_dt_ns = 50000000;  // 20 Hz
  std::int64_t imu_dt_ns = 5000000;     // 200 Hz
  bool patterned = false;  ///< images with a different value at every pixel (else one grey level per image)
};

/// Writes <dir>/mav0/... and returns the dataset root (dir).
std::string writeMiniDataset(const TempDir& dir, const MiniDatasetSpec& spec = {});

/// EuRoC-style camera sensor.yaml text (the real EuRoC cam0 calibration scaled to width x height).
std::string eurocCameraYaml(int cam, int width, int height);
std::string eurocImuYaml();

}  // namespace edgevio::test
