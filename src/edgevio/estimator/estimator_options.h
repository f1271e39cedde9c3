#pragma once
#include "edgevio/common/options.h"

namespace edgevio::estimator {

/// The sliding-window estimator (config section `estimator`; METHOD.md §4, §5).
struct EstimatorOptions {
  int window_size, max_iterations, realtime_pose_iterations;
  double huber_translation_m, huber_rotation_deg, damping, external_check_rotation_deg, external_check_translation_m,
      loop_check_rotation_deg, loop_check_translation_m, front_translation_m, front_rotation_deg,
      visual_covariance_scale, visual_shared_fraction, imu_noise_inflation, gyro_bias_walk_inflation,
      accel_bias_walk_inflation, max_imu_gap_s, repropagate_accel_bias, repropagate_gyro_bias, init_tilt_sigma_deg,
      init_velocity_sigma, init_accel_bias_sigma, init_gyro_bias_sigma, reset_accel_bias, reset_gyro_bias, reset_velocity, time_offset_sigma_ms,
      cam_imu_rotation_sigma_deg, cam_imu_translation_sigma_m;
  bool front_marginalization_drops_links, gauge_prior, first_estimate_jacobians, estimate_time_offset,
      estimate_cam_imu_rotation, estimate_cam_imu_translation;

  EDGEVIO_OPTIONS(EstimatorOptions)
};

// EstimatorOptions's keys, defaults, units, meanings and valid values: its table in estimator_options.cpp.

}  // namespace edgevio::estimator
