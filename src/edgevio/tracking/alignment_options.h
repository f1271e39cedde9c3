#pragma once
#include "edgevio/common/options.h"

namespace edgevio::tracking {

/// What a reference point's residual measures on the finest level (coarser
/// levels always use the distance transform, whose wide basin they are for).
enum class Residual { kPointToLine, kDistance };
inline constexpr options::Choice<Residual> kResidualChoices[] = {
    {Residual::kPointToLine, "point_to_line", "signed distance to the nearest sub-pixel edge line"},
    {Residual::kDistance, "distance", "the distance transform's value, the paper's eq 5"}};

/// The robust weight of a residual, from the point's distance d to the nearest edge.
enum class RobustWeight { kCauchy, kLaplacian };
inline constexpr options::Choice<RobustWeight> kRobustWeightChoices[] = {
    {RobustWeight::kCauchy, "cauchy", "w = 1/(1 + d^2/c^2)"},
    {RobustWeight::kLaplacian, "laplacian", "w = exp(-d), the paper's"}};

/// Edge alignment and its self check (config section `alignment`; METHOD.md §3).
struct AlignmentOptions {
  Residual residual;
  int max_iterations_per_level;
  double min_step;
  int max_stalled_iterations;
  RobustWeight weight;
  double cauchy_c2;
  int border_px, min_points, max_points;
  double max_normal_angle_deg, self_check_max_mean_distance_px, self_check_min_visible_ratio,
      self_check_max_translation_sigma_m;

  EDGEVIO_OPTIONS(AlignmentOptions)
};

// AlignmentOptions's keys, defaults, units, meanings and valid values: its table in alignment_options.cpp.

}  // namespace edgevio::tracking
