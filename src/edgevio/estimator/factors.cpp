#include "edgevio/estimator/factors.h"

#include <cmath>

namespace edgevio::estimator {

using geometry::SE3;

SE3 predictedRelativePose(const imu::NavState& r, const imu::NavState& n, const SE3& T_b_c) {
  return T_b_c.inverse() * SE3(n.R_w_b, n.p_w).inverse() * SE3(r.R_w_b, r.p_w) * T_b_c;
}

Vec6 relativePoseResidual(const SE3& T_meas, const imu::NavState& r, const imu::NavState& n, const SE3& T_b_c,
                          Mat6x15* J_r, Mat6x15* J_n, Mat6* J_extrinsics) {
  const SE3 A = T_b_c.inverse();
  const SE3 T_pred = predictedRelativePose(r, n, T_b_c);
  const Vec6 res = (T_meas.inverse() * T_pred).log();
  if (J_r || J_n || J_extrinsics) {
    const Mat6 JrInv = SE3::rightJacobianInverse(res);
    const Mat6 AdA = A.adjoint();
    const auto toState = [](const imu::NavState& s, const Mat6& d_dxi) {
      // ξ = (Rᵀδp, δθ): columns of δp are d/dρ · Rᵀ.
      Mat6x15 J = Mat6x15::Zero();
      J.block<6, 3>(0, imu::kP) = d_dxi.leftCols<3>() * s.R_w_b.inverse().matrix();
      J.block<6, 3>(0, imu::kR) = d_dxi.rightCols<3>();
      return J;
    };
    if (J_r) *J_r = toState(r, JrInv * AdA);
    if (J_n) *J_n = toState(n, -JrInv * T_pred.inverse().adjoint() * AdA);
    if (J_extrinsics) *J_extrinsics = JrInv * (Mat6::Identity() - T_pred.inverse().adjoint());
  }
  return res;
}

Mat6 huberWeightedInformation(const Mat6& info, const Vec6& res, double c_t, double c_a) {
  const double et = res.head<3>().norm(), ea = res.tail<3>().norm();
  const double wt = et > c_t ? c_t / et : 1.0, wa = ea > c_a ? c_a / ea : 1.0;
  Mat6 out = info;
  out.topLeftCorner<3, 3>() *= wt;
  out.bottomRightCorner<3, 3>() *= wa;
  const double wc = std::sqrt(wt * wa);
  out.topRightCorner<3, 3>() *= wc;
  out.bottomLeftCorner<3, 3>() *= wc;
  return out;
}

}  // namespace edgevio::estimator
