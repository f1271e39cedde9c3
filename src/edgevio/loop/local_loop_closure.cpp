#include "edgevio/loop/local_loop_closure.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "edgevio/tracking/edge_alignment.h"

namespace edgevio::loop {

using geometry::SE3;

double medianDepth(const tracking::KeyframeData& k) {
  if (k.depth.points.empty() || k.depth.points[0].empty()) return 0.0;
  std::vector<float> z;
  z.reserve(k.depth.points[0].size());
  for (const auto& p : k.depth.points[0]) z.push_back(p.z());
  std::nth_element(z.begin(), z.begin() + static_cast<long>(z.size() / 2), z.end());
  return z[z.size() / 2];
}

std::vector<LoopLink> closeLoops(const LoopKeyframe& latest, const std::vector<LoopKeyframe>& older, const LoopOptions& o,
                                 const tracking::AlignmentOptions& alignment, double budget_ms, LoopStats* stats_out) {
  const auto t0 = std::chrono::steady_clock::now();
  const auto elapsedMs = [&] { return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count(); };
  LoopStats stats;
  std::vector<LoopLink> links;
  const double depth = medianDepth(*latest.data);
  // Candidates by the estimates, skipping the newest keyframes (tracking links them already).
  std::vector<const LoopKeyframe*> sorted;
  for (const LoopKeyframe& k : older)
    if (k.data && k.data->t_ns < latest.data->t_ns) sorted.push_back(&k);
  std::sort(sorted.begin(), sorted.end(), [](const LoopKeyframe* a, const LoopKeyframe* b) { return a->data->t_ns > b->data->t_ns; });
  struct Candidate {
    const LoopKeyframe* k;
    double score;
  };
  std::vector<Candidate> candidates;
  for (std::size_t i = static_cast<std::size_t>(o.skip_recent_keyframes); i < sorted.size() && depth > 0; ++i) {
    const LoopKeyframe& k = *sorted[i];
    const double distance = (k.T_w_c.translation() - latest.T_w_c.translation()).norm();
    const Vec3 axis_k = k.T_w_c.so3() * Vec3::UnitZ(), axis_l = latest.T_w_c.so3() * Vec3::UnitZ();
    const double angle = std::acos(std::clamp(axis_k.dot(axis_l), -1.0, 1.0)) * kRadToDeg;
    const double d = distance / (o.max_distance_depth_ratio * depth), a = angle / o.max_view_angle_deg;
    if (d <= 1.0 && a <= 1.0) candidates.push_back({&k, d + a});
  }
  std::sort(candidates.begin(), candidates.end(), [](const Candidate& a, const Candidate& b) { return a.score < b.score; });
  stats.candidates = static_cast<int>(candidates.size());

  tracking::AlignmentOptions coarse = alignment;
  coarse.self_check_min_visible_ratio = o.coarse_min_visible_ratio;
  for (const Candidate& c : candidates) {
    if (stats.coarse_attempts >= o.max_coarse_attempts || stats.full_attempts >= o.max_full_attempts || elapsedMs() > budget_ms)
      break;
    ++stats.coarse_attempts;
    const tracking::KeyframeData& kc = *c.k->data;
    const tracking::KeyframeData& kn = *latest.data;
    const int top = static_cast<int>(std::min(kc.pyramid.levels.size(), kn.pyramid.levels.size())) - 1;
    if (top < 0) continue;
    const int level = std::min(o.cross_check_level, top);
    // Coarse self check threshold in that level's pixels.
    coarse.self_check_max_mean_distance_px = std::ldexp(o.coarse_max_mean_distance_px, level);
    const SE3 T_nc_init = latest.T_w_c.inverse() * c.k->T_w_c;
    const tracking::AlignmentResult a = tracking::alignEdges(kc.depth, kn.pyramid, T_nc_init, coarse, -1, level);
    const tracking::AlignmentResult b = tracking::alignEdges(kn.depth, kc.pyramid, T_nc_init.inverse(), coarse, -1, level);
    const SE3 E = a.T_nr * b.T_nr;
    const bool agree = E.translation().norm() <= o.max_disagreement_m && geometry::angle(E.so3()) * kRadToDeg <= o.max_disagreement_deg;
    if (!a.self_check_passed || !b.self_check_passed || !agree) {
      ++stats.cross_check_failures;
      continue;
    }
    ++stats.full_attempts;
    tracking::AlignmentOptions full = alignment;
    full.self_check_min_visible_ratio = o.min_visible_ratio;
    const tracking::AlignmentResult f = tracking::alignEdges(kc.depth, kn.pyramid, a.T_nr, full);
    if (!f.self_check_passed) continue;
    links.push_back({kc.t_ns, kn.t_ns, f.T_nr, f.covariance});
    ++stats.accepted;
  }
  stats.ms = elapsedMs();
  if (stats_out) *stats_out = stats;
  return links;
}

}  // namespace edgevio::loop
