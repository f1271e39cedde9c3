#pragma once
// Reference edges of a keyframe (METHOD.md §3): disparity by stereo block
// matching on the level-0 rectified pair, as floats (OpenCV's 1/16-px fixed
// point rounds up, on average by 0.027 px: a depth bias of a few tenths of a
// percent at EuRoC's baselines), inverse depth ρ = d/(f·b) at valid pixels
// (d ≥ min disparity), pooled up the pyramid as the inverse-variance mean of
// each pixel's valid 2x2 children, and the edge pixels of every level with a
// valid ρ back-projected: P = (1/ρ)·K⁻¹[u, v, 1]. On a level with edge lines
// (level 0), (u, v) is first moved along the edge normal onto its sub-pixel
// line, the edge the point-to-line residual of the current frame measures
// against: Canny's pixels are up to 0.5 px off it.
//
// Depth discontinuities (`vision.stereo_discontinuity_ratio` within
// `stereo_discontinuity_radius_px`): a block straddling an occlusion boundary
// matches the foreground, so background edges up to half a block beyond it
// take the foreground's depth, and the boundary's own edge pixels either
// side's. Such points move with the wrong parallax as the camera translates:
// a bias that grows with the link. Level 0 has no reference point where the
// valid inverse depths within the radius span more than the ratio. The
// coarser levels keep them: there the error is a fraction of a pixel, and the
// boundaries' strong edges give the alignment its basin.
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
  double baseline_m = 0.0;  ///< the stereo baseline b of ρ = d/(f·b)
  double bm_ms = 0.0;
};

/// `right_full`: the rectified right image at the camera resolution, as `left.full`.
KeyframeDepth computeKeyframeDepth(const EdgePyramid& left, const cv::Mat& right_full, double baseline_m,
                                   const VisionOptions& options);

}  // namespace edgevio::vision
