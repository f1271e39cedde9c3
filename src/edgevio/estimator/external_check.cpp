#include "edgevio/estimator/external_check.h"

namespace edgevio::estimator {

using geometry::SE3;

ExternalCheckResult externalCheck(const SE3& T_nr_measured, const imu::NavState& r, const imu::NavState& n_pred,
                                  const SE3& T_b_c, double max_rotation_deg, double max_translation_m) {
  const SE3 T_nr_pred = predictedRelativePose(r, n_pred, T_b_c);
  const SE3 E = T_nr_pred.inverse() * T_nr_measured;
  ExternalCheckResult res;
  res.rotation_deg = geometry::angle(E.so3()) * kRadToDeg;
  res.translation_m = (T_nr_measured.translation() - T_nr_pred.translation()).norm();
  res.accepted = res.rotation_deg <= max_rotation_deg && res.translation_m <= max_translation_m;
  return res;
}

}  // namespace edgevio::estimator
