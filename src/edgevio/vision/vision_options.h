#pragma once
#include <string>

namespace edgevio::vision {

/// Options of the front end's image processing (config section `vision`; METHOD.md §3).
struct VisionOptions {
  int levels = 4;                      ///< pyramid levels (376x240 ... 47x30 for EuRoC; paper: 3) [-]
  std::string canny_thresholds = "adaptive";  ///< adaptive (from Otsu) or fixed
  double canny_otsu_offset = 10.0;     ///< adaptive thresholds are (t − offset, t + offset), t = Otsu threshold [grey level]
  double canny_min_low = 20.0;         ///< lower clamp of the adaptive low threshold [gradient]
  double canny_max_high = 250.0;       ///< upper clamp of the adaptive high threshold [gradient]
  double canny_fixed_low = 40.0;       ///< fixed mode low threshold [gradient]
  double canny_fixed_high = 80.0;      ///< fixed mode high threshold [gradient]
  int stereo_num_disparities = 64;     ///< StereoBM search range at level 0 (multiple of 16) [px]
  int stereo_block_size = 13;          ///< StereoBM block (odd) [px]
  double stereo_min_disparity = 3.0;   ///< smaller level-0 disparities are invalid (too far) [px]
  double stereo_disparity_sigma = 0.5; ///< std. dev. of a block-matching disparity in the matched pair's pixels, for depth pooling [px]
  bool stereo_full_resolution = false; ///< also match the camera-resolution pair, pool it into level 0, keep it where it agrees
  int stereo_full_resolution_block_size = 21;  ///< its StereoBM block (odd) [full-resolution px]
  double stereo_full_resolution_max_difference_px = 1.0;  ///< kept where within this of the level-0 disparity [level-0 px]
  double stereo_discontinuity_ratio = 1.3;  ///< no reference point where the inverse depths within the radius span more than this factor; 0: off [-]
  int stereo_discontinuity_radius_px = 9;   ///< ... radius of that neighbourhood at level 0 [px]

  template <class Visitor>
  void visit(Visitor& v) {
    v("levels", levels, "-", "pyramid levels for coarse-to-fine alignment (level 0 = half the camera resolution)");
    v("canny_thresholds", canny_thresholds, "-", "adaptive (from each level's Otsu threshold) | fixed");
    v("canny_otsu_offset", canny_otsu_offset, "grey", "adaptive Canny thresholds are (t - offset, t + offset), t = Otsu");
    v("canny_min_low", canny_min_low, "grad", "lower clamp of the adaptive low threshold");
    v("canny_max_high", canny_max_high, "grad", "upper clamp of the adaptive high threshold");
    v("canny_fixed_low", canny_fixed_low, "grad", "fixed-mode low threshold");
    v("canny_fixed_high", canny_fixed_high, "grad", "fixed-mode high threshold");
    v("stereo_num_disparities", stereo_num_disparities, "px", "StereoBM disparity range at level 0 (multiple of 16)");
    v("stereo_block_size", stereo_block_size, "px", "StereoBM block size (odd) at level 0");
    v("stereo_min_disparity", stereo_min_disparity, "px", "smaller level-0 disparities are invalid");
    v("stereo_disparity_sigma", stereo_disparity_sigma, "px", "disparity std. dev. in the matched pair's pixels, weights depth pooling");
    v("stereo_full_resolution", stereo_full_resolution, "-", "also match the camera-resolution pair, pooled into level 0, kept where it agrees with level 0");
    v("stereo_full_resolution_block_size", stereo_full_resolution_block_size, "px", "its StereoBM block size (odd, full-resolution pixels)");
    v("stereo_full_resolution_max_difference_px", stereo_full_resolution_max_difference_px, "px", "kept where within this of the level-0 disparity (level-0 pixels)");
    v("stereo_discontinuity_ratio", stereo_discontinuity_ratio, "-", "no depth where the valid inverse depths within the radius span more than this factor (depth discontinuities); 0: off");
    v("stereo_discontinuity_radius_px", stereo_discontinuity_radius_px, "px", "radius of that neighbourhood at level 0");
  }
  std::string validate() const;
};

}  // namespace edgevio::vision
