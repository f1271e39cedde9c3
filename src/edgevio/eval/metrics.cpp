#include "edgevio/eval/metrics.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

#include "edgevio/common/error.h"
#include "edgevio/common/time.h"

namespace edgevio::eval {

using geometry::SE3;

namespace {
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string spanText(const io::Trajectory& t) {
  std::ostringstream o;
  o.precision(3);
  o << std::fixed << "[" << toSeconds(t.front().t_ns) << ", " << toSeconds(t.back().t_ns)
    << "] s";
  return o.str();
}
}  // namespace

double pathLength(const std::vector<SE3>& poses) {
  double d = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) d += (poses[i].translation() - poses[i - 1].translation()).norm();
  return d;
}

std::vector<std::pair<std::size_t, std::size_t>> rpePairsByPath(const std::vector<SE3>& poses, double delta_m) {
  std::vector<std::size_t> ids;
  double path = 0.0;
  for (std::size_t i = 1; i < poses.size(); ++i) {
    path += (poses[i].translation() - poses[i - 1].translation()).norm();
    if (path >= delta_m) {
      ids.push_back(i);
      path = 0.0;
    }
  }
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (std::size_t k = 1; k < ids.size(); ++k) pairs.emplace_back(ids[k - 1], ids[k]);
  return pairs;
}

RpeResult relativePoseError(const std::vector<SE3>& gt, const std::vector<SE3>& est, double delta_m) {
  RpeResult r;
  r.delta_m = delta_m;
  const auto pairs = rpePairsByPath(est, delta_m);
  r.pairs = pairs.size();
  if (pairs.empty()) {
    r.trans_rmse_m = r.rot_rmse_deg = kNaN;
    return r;
  }
  double se_t = 0.0, se_r = 0.0;
  for (const auto& [i, j] : pairs) {
    const SE3 E = (gt[i].inverse() * gt[j]).inverse() * (est[i].inverse() * est[j]);
    se_t += E.translation().squaredNorm();
    const double a = geometry::angle(E.so3()) * kRadToDeg;
    se_r += a * a;
  }
  r.trans_rmse_m = std::sqrt(se_t / static_cast<double>(pairs.size()));
  r.rot_rmse_deg = std::sqrt(se_r / static_cast<double>(pairs.size()));
  return r;
}

AreResult averageRelativeError(const std::vector<SE3>& gt, const std::vector<SE3>& est,
                               const std::vector<double>& lengths_m) {
  std::vector<double> dist(gt.size(), 0.0);
  for (std::size_t i = 1; i < gt.size(); ++i)
    dist[i] = dist[i - 1] + (gt[i].translation() - gt[i - 1].translation()).norm();
  AreResult r;
  double sum_rot = 0.0, sum_trans = 0.0;
  for (std::size_t i = 0; i < gt.size(); ++i) {
    for (double L : lengths_m) {
      if (!(L > 0.0)) continue;  // a static trajectory has no segments
      const auto it = std::lower_bound(dist.begin() + static_cast<long>(i), dist.end(), dist[i] + L);
      if (it == dist.end()) continue;
      const std::size_t j = static_cast<std::size_t>(it - dist.begin());
      const SE3 E = (gt[i].inverse() * gt[j]).inverse() * (est[i].inverse() * est[j]);
      sum_rot += geometry::angle(E.so3()) * kRadToDeg / L;
      sum_trans += E.translation().norm() / L;
      ++r.segments;
    }
  }
  if (r.segments == 0) {
    r.rot_deg_per_m = r.trans_m_per_m = kNaN;
  } else {
    r.rot_deg_per_m = sum_rot / static_cast<double>(r.segments);
    r.trans_m_per_m = sum_trans / static_cast<double>(r.segments);
  }
  return r;
}

EvalResult evaluate(const io::Trajectory& gt, const io::Trajectory& est, const EvalOptions& options) {
  EvalResult r;
  r.alignment = options.alignment;
  if (gt.empty() || est.empty()) throw InputError("empty trajectory");
  const auto tol = toNanoseconds(options.association_tolerance_s);
  const Association a = associate(gt, est, tol);
  if (a.size() == 0)
    throw InputError("no timestamp overlap: ground truth spans " + spanText(gt) + ", estimate spans " + spanText(est) +
                     " (tolerance " + std::to_string(options.association_tolerance_s) +
                     " s; are both in the same clock and unit?)");
  if (a.size() < minimumPoses(r.alignment))
    throw InputError("only " + std::to_string(a.size()) + " matched poses; " + alignmentName(r.alignment) +
                     " alignment needs at least " + std::to_string(minimumPoses(r.alignment)));
  r.matched = a.size();
  r.t_ns = a.t_ns;

  std::vector<Vec3> pe(a.size()), pg(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    pe[i] = a.est[i].translation();
    pg[i] = a.gt[i].translation();
  }
  r.transform = align(pe, pg, r.alignment);
  std::vector<SE3> est_aligned(a.size());
  for (std::size_t i = 0; i < a.size(); ++i) est_aligned[i] = r.transform.apply(a.est[i]);

  r.gt_positions = pg;
  for (std::size_t i = 0; i < a.size(); ++i) {
    r.est_positions_aligned.push_back(est_aligned[i].translation());
    r.ate_errors_m.push_back((pg[i] - est_aligned[i].translation()).norm());
  }
  const auto n = static_cast<double>(a.size());
  double se = 0.0;
  for (double e : r.ate_errors_m) se += e * e;
  r.ate_rmse_m = std::sqrt(se / n);
  r.ate_mean_m = std::accumulate(r.ate_errors_m.begin(), r.ate_errors_m.end(), 0.0) / n;
  std::vector<double> sorted = r.ate_errors_m;
  std::sort(sorted.begin(), sorted.end());
  const std::size_t m = sorted.size();
  r.ate_median_m = m % 2 ? sorted[m / 2] : 0.5 * (sorted[m / 2 - 1] + sorted[m / 2]);
  r.ate_max_m = sorted.back();

  for (double d : options.rpe_deltas_m) r.rpe.push_back(relativePoseError(a.gt, est_aligned, d));

  r.length_m = pathLength(a.gt);
  r.duration_s = toSeconds(a.t_ns.back() - a.t_ns.front());
  if (!options.are_segments_m.empty()) {
    r.are_lengths_m = options.are_segments_m;
  } else {
    for (double p : options.are_segments_percent) r.are_lengths_m.push_back(r.length_m * p / 100.0);
  }
  const AreResult are = averageRelativeError(a.gt, est_aligned, r.are_lengths_m);
  r.are_rot_deg_per_m = are.rot_deg_per_m;
  r.are_trans_m_per_m = are.trans_m_per_m;
  r.are_segments = are.segments;
  return r;
}

}  // namespace edgevio::eval
