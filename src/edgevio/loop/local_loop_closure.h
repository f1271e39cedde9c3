#pragma once
// Local loop closure (METHOD.md §6, paper §6.3). When a keyframe enters the
// window, older keyframes in the window that view the same place become
// candidates: camera centres within max_distance_depth_ratio × the new
// keyframe's median scene depth and optical axes within max_view_angle_deg,
// on the current estimates, cheapest (closest) first. Each candidate is
// cross-checked on the coarse levels (top of the pyramid down to
// cross_check_level): candidate → new and new → candidate are aligned
// independently from the estimates, both must pass a self check,
// and their composition T_nc·T_cn must be close to identity; a wrong place
// with similar texture converges to two inconsistent minima. Survivors are
// re-aligned through all levels and must pass the full self check. Attempts
// and time per keyframe are bounded. Each accepted pair is a loop link
// (candidate → new) with the alignment's covariance.
#include <memory>
#include <vector>

#include "edgevio/geometry/se3.h"
#include "edgevio/loop/loop_options.h"
#include "edgevio/tracking/alignment_options.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::loop {

/// A keyframe as loop closure sees it: its images and its current estimate.
struct LoopKeyframe {
  std::shared_ptr<const tracking::KeyframeData> data;
  geometry::SE3 T_w_c;  ///< rectified left camera in the world
};

struct LoopLink {
  std::int64_t t_ref_ns = 0, t_new_ns = 0;
  geometry::SE3 T_nr;  ///< maps points from the candidate's camera into the new keyframe's
  Mat6 covariance = Mat6::Identity();
};

struct LoopStats {
  int candidates = 0, coarse_attempts = 0, cross_check_failures = 0, full_attempts = 0, accepted = 0;
  double ms = 0.0;
};

/// Median depth of a keyframe's level-0 reference points (0 without points).
double medianDepth(const tracking::KeyframeData& keyframe);

/// Loop links from `older` (keyframes in the window, any order) to `latest`.
/// No new attempt starts after `budget_ms` (real time: loop.realtime_max_ms;
/// offline: infinity, so that the result does not depend on the machine).
std::vector<LoopLink> closeLoops(const LoopKeyframe& latest, const std::vector<LoopKeyframe>& older,
                                 const LoopOptions& options, const tracking::AlignmentOptions& alignment, double budget_ms,
                                 LoopStats* stats = nullptr);

}  // namespace edgevio::loop
