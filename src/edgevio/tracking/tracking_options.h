#pragma once
#include "edgevio/common/options.h"

namespace edgevio::tracking {

/// The keyframe policy, the checks of an alignment against its prediction,
/// and static initialisation (config section `tracking`; METHOD.md §3, §5).
struct TrackingOptions {
  double keyframe_edge_ratio;
  int keyframe_min_points;
  double keyframe_min_visible_ratio, gyro_check_deg;
  int gyro_check_realign_levels;
  double imu_translation_check_m, constant_velocity_max_accel_mps2, rotation_prior_deg, rotation_prior_fraction;
  int lost_after_failures;
  double lost_gyro_disagreement_deg;
  int lost_gyro_contradictions;
  double lost_accel_mps2, lost_speed_mps, lost_accel_disagreement_m, lost_accel_disagreement_mps2;
  double static_init_window_s, static_chunk_s, static_accel_std_max, static_gyro_std_max;

  EDGEVIO_OPTIONS(TrackingOptions)
};

// TrackingOptions's keys, defaults, units, meanings and valid values: its table in tracking_options.cpp.

}  // namespace edgevio::tracking
