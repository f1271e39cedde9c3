#pragma once
// Back links (not in METHOD.md; the window's modes). A tracking link measures
// the motion from a keyframe to a frame with the keyframe's stereo depth and
// the frame's edges. When that frame becomes a keyframe it has depth of its
// own, so the same motion can be measured the other way round: its reference
// points aligned into the previous keyframe's images. Depth and edges come
// from the other image, so the two measurements' errors are largely
// independent, and the window averages them; the next keyframes back are
// linked the same way while they overlap. Each result must pass the self check
// and agree with its initial guess, the estimated relative pose T_kl (for the
// previous keyframe: the tracking link itself), within max_disagreement:
//   ‖t(T_back · T_kl⁻¹)‖ ≤ max_disagreement_m,  ∠(T_back · T_kl⁻¹) ≤ max_disagreement_deg.
// Their effect on the EuRoC renders: docs/method-deviations.md.
#include <vector>

#include "edgevio/loop/back_link_options.h"
#include "edgevio/loop/local_loop_closure.h"

namespace edgevio::loop {

struct BackLinkStats {
  int attempts = 0, self_check_failures = 0, disagreements = 0, accepted = 0;
  double ms = 0.0;
};

/// Links from `latest` (its points) back into the keyframes of `previous`,
/// newest first, at most options.keyframes of them. `latest.T_w_c` must be
/// the tracker's pose (the tracking link), the others the window's estimates.
/// Each link maps points from the latest keyframe's camera into the older one's:
/// t_ref_ns = latest, t_new_ns = the older keyframe.
std::vector<LoopLink> backLinks(const LoopKeyframe& latest, const std::vector<LoopKeyframe>& previous,
                                const BackLinkOptions& options, const tracking::AlignmentOptions& alignment,
                                BackLinkStats* stats = nullptr);

}  // namespace edgevio::loop
