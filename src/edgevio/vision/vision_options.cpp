// The options table of VisionOptions (docs/configuration.md is generated from it).
#include "edgevio/vision/vision_options.h"

namespace edgevio::vision {

EDGEVIO_OPTIONS_TABLE(VisionOptions,
    number("levels", &S::levels, 4, "-",
           "pyramid levels of the coarse-to-fine alignment; level 0 is half the camera resolution (paper: 3)", closed(1, 6)),
    choice("canny_thresholds", &S::canny_thresholds, CannyThresholds::kAdaptive, kCannyThresholdChoices,
           "Canny thresholds of each level"),
    number("canny_otsu_offset", &S::canny_otsu_offset, 10.0, "grey", "the offset of the adaptive thresholds from Otsu's", atLeast(0)),
    number("canny_min_low", &S::canny_min_low, 20.0, "grad", "lower clamp of the adaptive low threshold", atLeast(0)),
    number("canny_max_high", &S::canny_max_high, 250.0, "grad", "upper clamp of the adaptive high threshold", above(0)),
    number("canny_fixed_low", &S::canny_fixed_low, 40.0, "grad", "fixed mode: low threshold", above(0)),
    number("canny_fixed_high", &S::canny_fixed_high, 80.0, "grad", "fixed mode: high threshold", above(0)),
    number("stereo_num_disparities", &S::stereo_num_disparities, 64, "px", "StereoBM disparity range at level 0",
           atLeast(16).multipleOf(16)),
    number("stereo_block_size", &S::stereo_block_size, 13, "px", "StereoBM block size at level 0", closed(5, 51).odd()),
    number("stereo_min_disparity", &S::stereo_min_disparity, 3.0, "px", "smaller level-0 disparities are invalid (too far)",
           atLeast(0)),
    number("stereo_disparity_sigma", &S::stereo_disparity_sigma, 0.5, "px",
           "std. dev. of a block-matching disparity, which weights the pooling of depth up the pyramid", above(0)),
    number("stereo_discontinuity_ratio", &S::stereo_discontinuity_ratio, 1.3, "-",
           "level 0 has no reference point where the valid inverse depths within the radius span more than this factor "
           "(a block straddling an occlusion boundary matches the foreground)",
           above(1).orOff()),
    number("stereo_discontinuity_radius_px", &S::stereo_discontinuity_radius_px, 9, "px",
           "radius of that neighbourhood at level 0", closed(1, 25)),
    Rule<S>{[](const S& s) { return s.canny_min_low < s.canny_max_high; }, "canny_min_low: must be below canny_max_high"},
    Rule<S>{[](const S& s) { return s.canny_fixed_low < s.canny_fixed_high; }, "canny_fixed_low: must be below canny_fixed_high"})

}  // namespace edgevio::vision
