#pragma once
// Trajectory error metrics (METHOD.md §8).
//
//  ATE  After alignment, e_i = ‖p_gt,i − (s R p_est,i + t)‖; RMSE, mean, median, max.
//  RPE  evo's consecutive-pair convention with a travelled-distance delta δ:
//       walking the (aligned) estimate, a pose index is kept each time the path
//       since the last kept one reaches δ; consecutive kept indices (i, j) form
//       pairs; E = (Q_i⁻¹Q_j)⁻¹(P_i⁻¹P_j) with Q ground truth, P estimate;
//       RMSE of ‖trans(E)‖ and of angle(E).
//  ARE  KITTI-style (Geiger 2012), the paper's metric: for every start frame i
//       and segment length L, j is the first frame whose ground-truth path from
//       i reaches L; E = (ΔT_gt)⁻¹ ΔT_est with ΔT = T_i⁻¹T_j; the averages over
//       all segments of angle(E)/L [deg/m] and ‖trans(E)‖/L [m/m].
#include <cstdint>
#include <vector>

#include "edgevio/eval/alignment.h"
#include "edgevio/eval/association.h"
#include "edgevio/eval/eval_options.h"
#include "edgevio/io/trajectory_io.h"

namespace edgevio::eval {

struct RpeResult {
  double delta_m = 0.0;
  std::size_t pairs = 0;       ///< 0 when the trajectory is shorter than δ (figures are NaN)
  double trans_rmse_m = 0.0;
  double rot_rmse_deg = 0.0;
};

struct EvalResult {
  std::size_t matched = 0;
  AlignmentKind alignment = AlignmentKind::kSe3;
  Similarity transform;          ///< maps the estimate into the ground-truth frame
  double ate_rmse_m = 0.0, ate_mean_m = 0.0, ate_median_m = 0.0, ate_max_m = 0.0;
  std::vector<RpeResult> rpe;
  double are_rot_deg_per_m = 0.0;
  double are_trans_m_per_m = 0.0;
  std::size_t are_segments = 0;
  std::vector<double> are_lengths_m;  ///< segment lengths used
  double length_m = 0.0;              ///< ground-truth path length over the matched poses
  double duration_s = 0.0;
  // Per matched pose, for plots.
  std::vector<std::int64_t> t_ns;
  std::vector<Vec3> gt_positions, est_positions_aligned;
  std::vector<double> ate_errors_m;
};

/// Evaluates `est` against `gt`. Throws InputError when there is no timestamp
/// overlap or too few matched poses for the alignment.
EvalResult evaluate(const io::Trajectory& gt, const io::Trajectory& est, const EvalOptions& options);

/// Lower-level pieces, exposed for tests.
std::vector<std::pair<std::size_t, std::size_t>> rpePairsByPath(const std::vector<geometry::SE3>& poses, double delta_m);
RpeResult relativePoseError(const std::vector<geometry::SE3>& gt, const std::vector<geometry::SE3>& est, double delta_m);
/// Returns {rot deg/m, trans m/m, segment count}.
struct AreResult {
  double rot_deg_per_m = 0.0, trans_m_per_m = 0.0;
  std::size_t segments = 0;
};
AreResult averageRelativeError(const std::vector<geometry::SE3>& gt, const std::vector<geometry::SE3>& est,
                               const std::vector<double>& lengths_m);
double pathLength(const std::vector<geometry::SE3>& poses);

}  // namespace edgevio::eval
