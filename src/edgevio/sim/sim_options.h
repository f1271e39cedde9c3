#pragma once
#include "edgevio/common/options.h"
#include "edgevio/sim/scene.h"

namespace edgevio::sim {

/// The simulator (config section `sim`). Command-line flags of `edgevio
/// simulate` override the options they name.
struct SimOptions {
  double knot_dt_s, max_trajectory_gap_s, trajectory_max_accel_mps2, trajectory_step_spread_s, static_start_s,
      scenario_duration_s;
  SceneOptions scene;
  double exposure_gain, image_noise_sigma, vignetting, stereo_brightness_mismatch, exposure_drift_amplitude,
      exposure_drift_period_s, lighting_change_interval_s, lighting_change_magnitude, blur_substep_ms,
      initial_gyro_bias_sigma, initial_accel_bias_sigma, imu_time_offset_ms;
  int png_compression, threads;

  EDGEVIO_OPTIONS(SimOptions)
};

// SimOptions's keys, defaults, units, meanings and valid values: its table in sim_options.cpp.

}  // namespace edgevio::sim
