#include "edgevio/loop/back_links.h"

#include <chrono>

#include "edgevio/tracking/edge_alignment.h"

namespace edgevio::loop {

using geometry::SE3;

std::vector<LoopLink> backLinks(const LoopKeyframe& latest, const std::vector<LoopKeyframe>& previous,
                                const BackLinkOptions& o, const tracking::AlignmentOptions& alignment,
                                BackLinkStats* stats_out) {
  const auto t0 = std::chrono::steady_clock::now();
  BackLinkStats stats;
  std::vector<LoopLink> links;
  for (std::size_t i = 0; i < previous.size() && static_cast<int>(i) < o.keyframes; ++i) {
    const LoopKeyframe& k = previous[i];
    if (!k.data || !latest.data) continue;
    ++stats.attempts;
    const SE3 T_kl = k.T_w_c.inverse() * latest.T_w_c;
    const tracking::AlignmentResult a = tracking::alignEdges(latest.data->depth, k.data->pyramid, T_kl, alignment);
    if (!a.self_check_passed) {
      ++stats.self_check_failures;
      continue;
    }
    const SE3 E = a.T_nr * T_kl.inverse();
    if (E.translation().norm() > o.max_disagreement_m || geometry::angle(E.so3()) * kRadToDeg > o.max_disagreement_deg) {
      ++stats.disagreements;
      continue;
    }
    links.push_back({latest.data->t_ns, k.data->t_ns, a.T_nr, a.covariance});
    ++stats.accepted;
  }
  stats.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (stats_out) *stats_out = stats;
  return links;
}

}  // namespace edgevio::loop
