#pragma once
// Reference edges of a keyframe (METHOD.md §3): disparity by stereo block
// matching on the level-0 rectified pair (optionally refined at full
// resolution, below), as floats (OpenCV's 1/16-px fixed point rounds up,
// 0.027 px on average, which made depths 0.3 % and every tracking link's
// translation 0.4-0.6 % short on the EuRoC renders), inverse depth
// ρ = d/(f·b) at valid pixels (d ≥ min disparity), pooled up the pyramid as
// the inverse-variance mean of each pixel's valid 2x2 children, and the edge
// pixels of every level with a valid ρ back-projected: P = (1/ρ)·K⁻¹[u, v, 1].
// On a level with edge lines (level 0), (u, v) is first moved along the edge
// normal onto its sub-pixel line, the edge the point-to-line residual of the
// current frame measures against: Canny's pixels are up to 0.5 px off it,
// which biased near-identical views (median link error 11-20 % lower on the
// EuRoC renders).
//
// Depth discontinuities (`vision.stereo_discontinuity_ratio`, 1.3, within
// `stereo_discontinuity_radius_px`, 9): a 13 px block straddling an occlusion
// boundary matches the foreground, so background edges up to half a block
// beyond it take the foreground's depth, and the boundary's own edge pixels
// either side's. Such points move with the wrong parallax as the camera
// translates: a bias that grows with the link. Level 0 has no reference point
// where the valid inverse depths within the radius span more than the ratio
// (on the figure8 render: points off by more than 10 % 2.4 % → 1.1 %, 96 % of
// the points on smooth surfaces kept). The coarser levels keep them: there
// the error is a fraction of a pixel, and the boundaries' strong edges give
// the alignment its basin (five frames apart from identity, one view in six
// converged 0.9 m off without them).
//
// `vision.stereo_full_resolution` (off by default) also matches the
// camera-resolution pair (21 px blocks), pools it into level 0 and keeps it
// where it lies within 1 px of the level-0 disparity. It lowers the median
// depth error on smooth surfaces from 0.70 % to 0.52 % (test below). Unchecked,
// it took the 18 EuRoC renders' edge+imu ATE sum from 1.237 to 1.053 m, but 2
// of 21 keyframes of the near figure8 room aligned 1.3-1.8 cm off from one
// frame away (`convergence_basin_bench`); where the two resolutions disagree,
// one matched the wrong block. Checked: figure8 as with level-0 matching, the
// EuRoC sum 1.165 m, at 35 instead of 5.5 ms per keyframe. Hence off.
#include <Eigen/Core>
#include <opencv2/core.hpp>

#include <vector>

#include "edgevio/vision/edge_pyramid.h"

namespace edgevio::vision {

struct KeyframeDepth {
  /// Per level: reference points in the keyframe's rectified left camera frame [m].
  std::vector<std::vector<Eigen::Vector3f>> points;
  /// Per level: the unit normal (grey-level gradient direction) of each
  /// point's edge in the keyframe's image, where the level has edge lines
  /// (level 0); empty on the other levels.
  std::vector<std::vector<Eigen::Vector2f>> normals;
  double bm_ms = 0.0;
};

/// `right_full`: the rectified right image at the camera resolution, as `left.full`.
KeyframeDepth computeKeyframeDepth(const EdgePyramid& left, const cv::Mat& right_full, double baseline_m,
                                   const VisionOptions& options);

}  // namespace edgevio::vision
