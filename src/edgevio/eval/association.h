#pragma once
// Timestamp association of an estimate with ground truth (METHOD.md §8), with
// the evo convention: the shorter trajectory is the reference; each of its
// poses is matched to the nearest-in-time pose of the other (the first one on
// ties) when |Δt| ≤ tolerance. Pairs keep the order of the shorter trajectory.
#include <cstdint>
#include <vector>

#include "edgevio/io/trajectory_io.h"

namespace edgevio::eval {

struct Association {
  std::vector<std::int64_t> t_ns;  ///< timestamps of the ground-truth poses
  std::vector<geometry::SE3> gt;   ///< T_w_b of the ground truth
  std::vector<geometry::SE3> est;  ///< T_w_b of the estimate (in its own world frame)
  std::size_t size() const { return gt.size(); }
};

Association associate(const io::Trajectory& gt, const io::Trajectory& est, std::int64_t tolerance_ns);

}  // namespace edgevio::eval
