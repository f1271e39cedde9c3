#pragma once
#include <string>

namespace edgevio::tracking {

/// Options of edge alignment and the self check (config section `alignment`; METHOD.md §3).
struct AlignmentOptions {
  std::string residual = "point_to_line";     ///< point_to_line: signed distance to the nearest sub-pixel edge line | distance: V (paper)
  int max_iterations_per_level = 20;          ///< Gauss-Newton iterations per pyramid level [-]
  double min_step = 1e-5;                     ///< stop a level when |ξ| falls below this [m, rad]
  int max_stalled_iterations = 3;             ///< stop a level after this many iterations without a better mean distance [-]
  std::string weight = "cauchy";              ///< cauchy: w = 1/(1 + υ²/c²) | laplacian: w = exp(−υ) (paper)
  double cauchy_c2 = 1.5;                     ///< c² of the Cauchy weight [px²]
  int border_px = 2;                          ///< points must land in [b, W−1−b]x[b, H−1−b] [px]
  int min_points = 30;                        ///< fewer visible points at a level: the level is skipped [-]
  int max_points = 3000;                      ///< at most this many reference points per level, evenly strided; 0 = all [-]
  double max_normal_angle_deg = 45.0;         ///< finest level: a point whose nearest edge's normal is farther than this from its own (mapped into the current image) gets weight 0; 0: off [deg]
  double self_check_max_mean_distance_px = 5.0;  ///< self check: mean υ at level 0 at most this [px]
  double self_check_min_visible_ratio = 0.5;     ///< self check: at least this fraction of points in the image [-]
  double self_check_max_translation_sigma_m = 0.2;  ///< self check: σ of the translation along its weakest direction at most this (1 level-0 px of edge noise) [m]

  template <class Visitor>
  void visit(Visitor& v) {
    v("residual", residual, "-", "point_to_line: signed distance to the nearest sub-pixel edge line | distance: DT value (paper)");
    v("max_iterations_per_level", max_iterations_per_level, "-", "Gauss-Newton iterations per pyramid level");
    v("min_step", min_step, "m|rad", "a level stops when the step norm falls below this");
    v("max_stalled_iterations", max_stalled_iterations, "-", "a level stops after this many iterations without improvement");
    v("weight", weight, "-", "cauchy: w = 1/(1 + d^2/c^2) | laplacian: w = exp(-d) (paper); d = distance to the nearest edge");
    v("cauchy_c2", cauchy_c2, "px^2", "c^2 of the Cauchy weight");
    v("border_px", border_px, "px", "points must project at least this far inside the image");
    v("min_points", min_points, "-", "a level with fewer visible points is skipped");
    v("max_points", max_points, "-", "at most this many reference points per level (even stride); 0 = all");
    v("max_normal_angle_deg", max_normal_angle_deg, "deg", "finest level: weight 0 for a point whose nearest edge's signed normal is farther than this from its own edge's (0: off)");
    v("self_check_max_mean_distance_px", self_check_max_mean_distance_px, "px", "self check: mean distance at level 0");
    v("self_check_min_visible_ratio", self_check_min_visible_ratio, "-", "self check: fraction of points in the image");
    v("self_check_max_translation_sigma_m", self_check_max_translation_sigma_m, "m",
      "self check: std. dev. of the translation along its weakest direction, for 1 px of edge noise (a collapsed fit: all points on one spot)");
  }
  std::string validate() const;
};

}  // namespace edgevio::tracking
