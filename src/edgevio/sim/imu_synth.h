#pragma once
// IMU synthesis from a SplineTrajectory (issue #4; METHOD.md §2, §4):
//   ω̂ = ω_b + b_g + n_g,   â = R_w_bᵀ (a_w + g) + b_a + n_a,   g = [0, 0, 9.81],
// so an IMU at rest reads +9.81 on its up axis. Discrete noise from the
// continuous densities σ: white noise σ·√rate per sample, bias random walk
// σ_b·√Δt per sample; initial biases drawn once. Everything from the seed.
#include <cstdint>
#include <vector>

#include "edgevio/camera/calibration.h"
#include "edgevio/imu/imu_types.h"
#include "edgevio/sim/spline_trajectory.h"

namespace edgevio::sim {

constexpr double kGravity = 9.81;

struct ImuSynthOptions {
  bool noise = true;                     ///< white noise, random walk and initial biases; false: exact readings
  imu::ImuNoise densities;            ///< continuous-time densities
  double initial_gyro_bias_sigma = 0.003;   ///< [rad/s]
  double initial_accel_bias_sigma = 0.05;   ///< [m/s²]
};

struct SynthesizedImu {
  std::vector<imu::ImuSample> samples;
  std::vector<Vec3> b_g, b_a;  ///< true biases at each sample
};

/// Samples at densities.rate_hz from begin_ns to end_ns (inclusive).
SynthesizedImu synthesizeImu(const SplineTrajectory& trajectory, std::int64_t begin_ns, std::int64_t end_ns,
                             const ImuSynthOptions& options, std::uint64_t seed);

}  // namespace edgevio::sim
