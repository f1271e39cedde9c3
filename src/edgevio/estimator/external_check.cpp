#include "edgevio/estimator/external_check.h"

namespace edgevio::estimator {

using geometry::SE3;
using geometry::SO3;

imu::NavState predictState(const imu::NavState& r, const imu::Preintegration& pre) {
  // Deltas corrected to first order for r's biases (as in the residual).
  const Vec3 dba = r.b_a - pre.linearizationBa(), dbg = r.b_g - pre.linearizationBg();
  const imu::Mat15& J = pre.jacobian();
  const Vec3 alpha = pre.alpha() + J.block<3, 3>(imu::kP, imu::kBa) * dba + J.block<3, 3>(imu::kP, imu::kBg) * dbg;
  const Vec3 beta = pre.beta() + J.block<3, 3>(imu::kV, imu::kBa) * dba + J.block<3, 3>(imu::kV, imu::kBg) * dbg;
  const SO3 gamma = pre.gamma() * SO3::exp(J.block<3, 3>(imu::kR, imu::kBg) * dbg);
  const double T = pre.deltaT();
  imu::NavState n = r;
  n.R_w_b = r.R_w_b * gamma;
  n.p_w = r.p_w + r.v_w * T - 0.5 * imu::gravity() * T * T + (r.R_w_b * alpha);
  n.v_w = r.v_w - imu::gravity() * T + (r.R_w_b * beta);
  return n;
}

ExternalCheckResult externalCheck(const SE3& T_nr_measured, const imu::NavState& r, const imu::NavState& n_pred,
                                  const SE3& T_b_c, double max_rotation_deg, double max_translation_m) {
  const SE3 C_r = SE3(r.R_w_b, r.p_w) * T_b_c, C_n = SE3(n_pred.R_w_b, n_pred.p_w) * T_b_c;
  const SE3 T_nr_pred = C_n.inverse() * C_r;
  const SE3 E = T_nr_pred.inverse() * T_nr_measured;
  ExternalCheckResult res;
  res.rotation_deg = geometry::angle(E.so3()) * 180.0 / kPi;
  res.translation_m = (T_nr_measured.translation() - T_nr_pred.translation()).norm();
  res.accepted = res.rotation_deg <= max_rotation_deg && res.translation_m <= max_translation_m;
  return res;
}

}  // namespace edgevio::estimator
