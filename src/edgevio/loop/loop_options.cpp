// The options table of LoopOptions (docs/configuration.md is generated from it).
#include "edgevio/loop/loop_options.h"

namespace edgevio::loop {

EDGEVIO_OPTIONS_TABLE(LoopOptions,
    number("max_distance_depth_ratio", &S::max_distance_depth_ratio, 0.5, "-",
           "a candidate's camera centre is closer than this times the new keyframe's median scene depth", above(0)),
    number("max_view_angle_deg", &S::max_view_angle_deg, 30.0, "deg", "a candidate's optical axis is closer than this",
           Range{0, 180, true, false}),
    number("skip_recent_keyframes", &S::skip_recent_keyframes, 1, "-",
           "the newest keyframes before the new one are no candidates (tracking links them)", atLeast(0)),
    number("cross_check_level", &S::cross_check_level, 1, "-",
           "the cross check aligns from the pyramid's top down to this level (1: 188x120; the paper's 94x60 was too coarse)",
           atLeast(0)),
    number("max_coarse_attempts", &S::max_coarse_attempts, 4, "-", "candidates cross-checked on the coarse levels per keyframe",
           atLeast(0)),
    number("max_full_attempts", &S::max_full_attempts, 2, "-", "survivors aligned again through all levels per keyframe",
           atLeast(0)),
    number("realtime_max_ms", &S::realtime_max_ms, 20.0, "ms",
           "real-time runs only: no new attempt starts after this much loop-closure time per keyframe (offline runs are "
           "bounded by the attempt counts alone, so that they do not depend on the machine)",
           above(0)),
    number("coarse_max_mean_distance_px", &S::coarse_max_mean_distance_px, 1.0, "px",
           "coarse self check: mean distance at cross_check_level, in that level's pixels", above(0)),
    number("coarse_min_visible_ratio", &S::coarse_min_visible_ratio, 0.3, "-", "coarse self check: fraction of the points in view",
           closed(0, 1)),
    number("max_disagreement_m", &S::max_disagreement_m, 0.05, "m",
           "cross check: the composition of both directions, translation off identity", above(0)),
    number("max_disagreement_deg", &S::max_disagreement_deg, 1.5, "deg", "... and rotation off identity", above(0)),
    number("min_visible_ratio", &S::min_visible_ratio, 0.4, "-", "full alignment's self check: fraction of level-0 points in view",
           closed(0, 1)))

}  // namespace edgevio::loop
