#pragma once
#include "edgevio/common/options.h"

namespace edgevio::vision {

/// How the Canny thresholds of a level are chosen (METHOD.md §3).
enum class CannyThresholds { kAdaptive, kFixed };
inline constexpr options::Choice<CannyThresholds> kCannyThresholdChoices[] = {
    {CannyThresholds::kAdaptive, "adaptive", "from each level's Otsu threshold t: (t - offset, t + offset), clamped"},
    {CannyThresholds::kFixed, "fixed", "canny_fixed_low and canny_fixed_high"}};

/// The front end's image processing: pyramid, Canny, keyframe stereo depth
/// (config section `vision`; METHOD.md §3).
struct VisionOptions {
  int levels;
  CannyThresholds canny_thresholds;
  double canny_otsu_offset, canny_min_low, canny_max_high, canny_fixed_low, canny_fixed_high;
  int stereo_num_disparities, stereo_block_size;
  double stereo_min_disparity, stereo_disparity_sigma, stereo_discontinuity_ratio;
  int stereo_discontinuity_radius_px;

  EDGEVIO_OPTIONS(VisionOptions)
};

// VisionOptions's keys, defaults, units, meanings and valid values: its table in vision_options.cpp.

}  // namespace edgevio::vision
