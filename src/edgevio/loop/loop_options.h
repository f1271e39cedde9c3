#pragma once
#include "edgevio/common/options.h"

namespace edgevio::loop {

/// Local loop closure (config section `loop`; METHOD.md §6).
struct LoopOptions {
  double max_distance_depth_ratio, max_view_angle_deg;
  int skip_recent_keyframes, cross_check_level, max_coarse_attempts, max_full_attempts;
  double realtime_max_ms, coarse_max_mean_distance_px, coarse_min_visible_ratio, max_disagreement_m,
      max_disagreement_deg, min_visible_ratio;

  EDGEVIO_OPTIONS(LoopOptions)
};

// LoopOptions's keys, defaults, units, meanings and valid values: its table in loop_options.cpp.

}  // namespace edgevio::loop
