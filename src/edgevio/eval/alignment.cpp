#include "edgevio/eval/alignment.h"

#include <Eigen/SVD>
#include <cmath>

namespace edgevio::eval {

std::size_t minimumPoses(AlignmentKind kind) {
  switch (kind) {
    case AlignmentKind::kSe3:
    case AlignmentKind::kSim3: return 3;
    case AlignmentKind::kPosYaw: return 2;
    case AlignmentKind::kNone: return 1;
  }
  return 1;
}

Similarity align(const std::vector<Vec3>& est, const std::vector<Vec3>& gt, AlignmentKind kind) {
  Similarity s;
  if (kind == AlignmentKind::kNone || est.empty()) return s;
  const double n = static_cast<double>(est.size());
  Vec3 mu_e = Vec3::Zero(), mu_g = Vec3::Zero();
  for (std::size_t i = 0; i < est.size(); ++i) {
    mu_e += est[i];
    mu_g += gt[i];
  }
  mu_e /= n;
  mu_g /= n;

  if (kind == AlignmentKind::kPosYaw) {
    // Minimise Σ|g_i − Rz(ψ) e_i − t|²: with centred points the optimal ψ is
    // atan2(Σ (e_x g_y − e_y g_x), Σ (e_x g_x + e_y g_y)); z only shifts.
    double num = 0.0, den = 0.0;
    for (std::size_t i = 0; i < est.size(); ++i) {
      const Vec3 e = est[i] - mu_e, g = gt[i] - mu_g;
      num += e.x() * g.y() - e.y() * g.x();
      den += e.x() * g.x() + e.y() * g.y();
    }
    const geometry::SO3 R = geometry::SO3::exp(Vec3(0.0, 0.0, std::atan2(num, den)));
    s.T = geometry::SE3(R, mu_g - R * mu_e);
    return s;
  }

  // Umeyama, "Least-squares estimation of transformation parameters between two
  // point patterns", PAMI 1991, eqs 38-42.
  Mat3 cov = Mat3::Zero();
  double var_e = 0.0;
  for (std::size_t i = 0; i < est.size(); ++i) {
    const Vec3 e = est[i] - mu_e, g = gt[i] - mu_g;
    cov += g * e.transpose();
    var_e += e.squaredNorm();
  }
  cov /= n;
  var_e /= n;
  const Eigen::JacobiSVD<Mat3> svd(cov, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 S = Mat3::Identity();
  if (svd.matrixU().determinant() * svd.matrixV().determinant() < 0.0) S(2, 2) = -1.0;
  const Mat3 R = svd.matrixU() * S * svd.matrixV().transpose();
  if (kind == AlignmentKind::kSim3 && var_e > 0.0) s.scale = (svd.singularValues().asDiagonal() * S).trace() / var_e;
  s.T = geometry::SE3(geometry::SO3::fromMatrix(R), mu_g - s.scale * (R * mu_e));
  return s;
}

}  // namespace edgevio::eval
