#pragma once
#include "edgevio/common/options.h"

namespace edgevio::estimator {

/// How the window uses a tracking link (METHOD.md §5; keyframe_structure.h).
enum class Coupling { kSemiTight, kTight };
inline constexpr options::Choice<Coupling> kCouplingChoices[] = {
    {Coupling::kSemiTight, "semi_tight", "the alignment's relative pose with its covariance (the paper's)"},
    {Coupling::kTight, "tight",
     "the edge residuals of the keyframe's reference points in the frame, their inverse depths estimated in the window"}};

/// The sliding-window estimator (config section `estimator`; METHOD.md §4, §5).
struct EstimatorOptions {
  int window_size, max_iterations, realtime_pose_iterations;
  Coupling coupling;
  int tight_points;
  double tight_pixel_sigma_px, tight_huber_px, tight_disparity_sigma_px;
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
