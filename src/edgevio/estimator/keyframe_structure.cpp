#include "edgevio/estimator/keyframe_structure.h"

#include <algorithm>
#include <cmath>

#include "edgevio/tracking/edge_alignment.h"

namespace edgevio::estimator {

namespace {

// valueAndGradient reads a 4x4 neighbourhood: a point must land 2 px inside
// the image (the alignment's default border_px).
constexpr int kBorderPx = 2;
// The smallest inverse depth back-substitution leaves: 1 km, farther than any
// point stereo can measure, so a step through zero cannot flip a point behind.
constexpr double kMinInverseDepth = 1e-3;

}  // namespace

KeyframePoints selectKeyframePoints(const vision::KeyframeDepth& depth, const vision::LevelCamera& level0, int max_points,
                                    double disparity_sigma_px, double max_normal_angle_deg) {
  KeyframePoints kp;
  if (depth.points.empty() || depth.points[0].empty() || max_points <= 0 || !(depth.baseline_m > 0)) return kp;
  const std::vector<Eigen::Vector3f>& pts = depth.points[0];
  const std::size_t n = pts.size(), take = std::min<std::size_t>(n, static_cast<std::size_t>(max_points));
  const bool with_normals = max_normal_angle_deg > 0 && depth.normals.size() == depth.points.size() && depth.normals[0].size() == n;
  for (std::size_t k = 0; k < take; ++k) {
    const std::size_t idx = k * n / take;
    const Vec3 P = pts[idx].cast<double>();
    if (!(P.z() > 0)) continue;
    kp.rays.push_back(P / P.z());
    kp.rho_stereo.push_back(1.0 / P.z());
    if (with_normals) kp.normals.push_back(depth.normals[0][idx]);
  }
  if (with_normals) kp.min_normal_cos = std::cos(max_normal_angle_deg * kDegToRad);
  kp.rho = kp.rho_stereo;
  const double sigma_rho = disparity_sigma_px / (level0.fx * depth.baseline_m);
  kp.rho_information = 1.0 / (sigma_rho * sigma_rho);
  return kp;
}

StructureSystem linearizeStructure(const KeyframePoints& kp, const std::vector<StructureLink>& links,
                                   const EdgeWeighting& w, bool cost_only) {
  StructureSystem s;
  const long k = static_cast<long>(links.size());
  if (!cost_only) {
    s.H = Eigen::MatrixXd::Zero(6 * k, 6 * k);
    s.g = Eigen::VectorXd::Zero(6 * k);
    s.points.resize(kp.rays.size());
  }
  const double info = 1.0 / (w.sigma_px * w.sigma_px);
  for (std::size_t i = 0; i < kp.rays.size(); ++i) {
    const double rho = kp.rho[i], d_rho = rho - kp.rho_stereo[i];
    s.cost += 0.5 * kp.rho_information * d_rho * d_rho;
    StructureSystem::Point* pt = cost_only ? nullptr : &s.points[i];
    if (pt) {
      pt->h_rho = kp.rho_information;
      pt->g_rho = kp.rho_information * d_rho;
    }
    const Vec3 P = kp.rays[i] / rho;
    for (long a = 0; a < k; ++a) {
      const vision::EdgeLevel& level = links[static_cast<std::size_t>(a)].image->levels.front();
      double r = 0.0, normal_cos = 1.0;
      tracking::Jacobian16 J;
      if (!tracking::edgeResidual(P, links[static_cast<std::size_t>(a)].T_nr, level.camera, level.dt, kBorderPx, &r,
                                  cost_only ? nullptr : &J, true, nullptr, kp.normals.empty() ? nullptr : &kp.normals[i],
                                  &normal_cos) ||
          normal_cos < kp.min_normal_cos)
        continue;
      ++s.residuals;
      // Huber: ½r² inside, c|r| − ½c² beyond; Gauss-Newton with the weight min(1, c/|r|).
      const double c = w.huber_px, abs_r = std::abs(r);
      s.cost += info * (abs_r <= c ? 0.5 * r * r : c * abs_r - 0.5 * c * c);
      if (cost_only) continue;
      const double W = info * (abs_r <= c ? 1.0 : c / abs_r);
      // ∂υ/∂P = the first three columns of ∂υ/∂ξ (T·exp(ξ)·P moves by R·δp, T·P by R·δP); ∂P/∂ρ = −ray/ρ².
      const Vec6 Jxi = J.transpose();
      const double J_rho = -Jxi.head<3>().dot(kp.rays[i]) / (rho * rho);
      s.H.block<6, 6>(6 * a, 6 * a) += W * Jxi * Jxi.transpose();
      s.g.segment<6>(6 * a) += W * r * Jxi;
      pt->h_rho += W * J_rho * J_rho;
      pt->g_rho += W * J_rho * r;
      pt->coupling.emplace_back(static_cast<int>(a), W * J_rho * Jxi);
    }
  }
  if (cost_only) return s;
  // Schur complement of each ρ_i (its block is the scalar h_rho): H −= Σ_i
  // c_i c_iᵀ and g −= Σ_i c_i g_ρ/√h_ρ with c_i = h_i/√h_ρ, the c_i as the
  // columns of one matrix, so that the sum is one rank update.
  long seen = 0;
  for (const StructureSystem::Point& pt : s.points) seen += pt.coupling.empty() ? 0 : 1;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(6 * k, seen);
  long col = 0;
  for (const StructureSystem::Point& pt : s.points) {
    if (pt.coupling.empty()) continue;
    const double scale = 1.0 / std::sqrt(pt.h_rho);
    for (const auto& [a, ha] : pt.coupling) C.block<6, 1>(6 * a, col) = ha * scale;
    s.g.noalias() -= C.col(col) * (pt.g_rho * scale);
    ++col;
  }
  s.H.selfadjointView<Eigen::Lower>().rankUpdate(C, -1.0);
  s.H.triangularView<Eigen::StrictlyUpper>() = s.H.transpose();
  return s;
}

void updateInverseDepths(const StructureSystem& s, const Eigen::VectorXd& dxi, KeyframePoints* kp) {
  for (std::size_t i = 0; i < s.points.size(); ++i) {
    const StructureSystem::Point& pt = s.points[i];
    double rhs = pt.g_rho;
    for (const auto& [a, ha] : pt.coupling) rhs += ha.dot(dxi.segment<6>(6 * a));
    kp->rho[i] = std::max(kMinInverseDepth, kp->rho[i] - rhs / pt.h_rho);
  }
}

}  // namespace edgevio::estimator
