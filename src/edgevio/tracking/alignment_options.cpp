// The options table of AlignmentOptions (docs/configuration.md is generated from it).
#include "edgevio/tracking/alignment_options.h"

namespace edgevio::tracking {

EDGEVIO_OPTIONS_TABLE(AlignmentOptions,
    choice("residual", &S::residual, Residual::kPointToLine, kResidualChoices, "residual of a reference point on the finest level"),
    number("max_iterations_per_level", &S::max_iterations_per_level, 20, "-", "Gauss-Newton iterations per pyramid level", closed(1, 100)),
    number("min_step", &S::min_step, 1e-5, "m|rad", "a level stops when the step's norm falls below this", above(0)),
    number("max_stalled_iterations", &S::max_stalled_iterations, 3, "-",
           "a level stops after this many iterations without a lower mean distance", atLeast(1)),
    choice("weight", &S::weight, RobustWeight::kCauchy, kRobustWeightChoices,
           "robust weight of a residual, d = the point's distance to the nearest edge"),
    number("cauchy_c2", &S::cauchy_c2, 1.5, "px^2", "c^2 of the Cauchy weight", above(0)),
    number("border_px", &S::border_px, 2, "px", "points must project at least this far inside the image", closed(1, 20)),
    number("min_points", &S::min_points, 30, "-", "a level with fewer visible points is skipped", atLeast(6)),
    number("max_points", &S::max_points, 3000, "-", "at most this many reference points per level, evenly strided",
           atLeast(1).orOff()),
    number("max_normal_angle_deg", &S::max_normal_angle_deg, 45.0, "deg",
           "finest level: weight 0 for a point whose nearest edge's signed normal is farther than this from its own edge's",
           closed(0, 180)),
    number("self_check_max_mean_distance_px", &S::self_check_max_mean_distance_px, 5.0, "px",
           "self check: the mean distance of the visible points to the nearest edge at the finest level", above(0)),
    number("self_check_min_visible_ratio", &S::self_check_min_visible_ratio, 0.5, "-",
           "self check: the fraction of the reference points that land in the image", closed(0, 1)),
    number("self_check_max_translation_sigma_m", &S::self_check_max_translation_sigma_m, 0.2, "m",
           "self check: std. dev. of the translation along its weakest direction, for 1 px of edge noise (a fit "
           "collapsed onto one spot of an edge fixes only a ray)",
           above(0)),
    Rule<S>{[](const S& s) { return s.max_points == 0 || s.max_points >= s.min_points; }, "max_points: 0 (all) or at least min_points"})

}  // namespace edgevio::tracking
