#include "edgevio/eval/association.h"

#include <algorithm>

namespace edgevio::eval {

namespace {
/// Index of the sample of `traj` nearest to t (first of equals), or -1 if none within tol.
long nearest(const io::Trajectory& traj, std::int64_t t, std::int64_t tol) {
  const auto it = std::lower_bound(traj.begin(), traj.end(), t,
                                   [](const io::TrajectorySample& s, std::int64_t v) { return s.t_ns < v; });
  long best = -1;
  std::int64_t best_diff = 0;
  const auto consider = [&](long i) {
    if (i < 0 || i >= static_cast<long>(traj.size())) return;
    const std::int64_t d = std::llabs(traj[static_cast<std::size_t>(i)].t_ns - t);
    if (best < 0 || d < best_diff) {
      best = i;
      best_diff = d;
    }
  };
  const long i = static_cast<long>(it - traj.begin());
  consider(i - 1);
  consider(i);
  if (best < 0 || best_diff > tol) return -1;
  while (best > 0 && traj[static_cast<std::size_t>(best - 1)].t_ns == traj[static_cast<std::size_t>(best)].t_ns) --best;
  return best;
}
}  // namespace

Association associate(const io::Trajectory& gt, const io::Trajectory& est, std::int64_t tolerance_ns) {
  Association a;
  const bool est_is_short = est.size() <= gt.size();
  const io::Trajectory& shorter = est_is_short ? est : gt;
  const io::Trajectory& longer = est_is_short ? gt : est;
  for (const auto& s : shorter) {
    const long j = nearest(longer, s.t_ns, tolerance_ns);
    if (j < 0) continue;
    const io::TrajectorySample& o = longer[static_cast<std::size_t>(j)];
    const io::TrajectorySample& g = est_is_short ? o : s;
    const io::TrajectorySample& e = est_is_short ? s : o;
    a.t_ns.push_back(g.t_ns);
    a.gt.push_back(g.T_w_b);
    a.est.push_back(e.T_w_b);
  }
  return a;
}

}  // namespace edgevio::eval
