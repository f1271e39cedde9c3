#pragma once
// IMU-aided external check (METHOD.md §5, paper §6.4): before a tracking link
// enters the window, compare it with the IMU's prediction of the same
// relative motion; reject it when the rotation differs by more than
// max_rotation_deg or the translation by more than max_translation_m. A
// rejected link is dropped and the frame becomes a keyframe (caller's part).
#include "edgevio/estimator/factors.h"
#include "edgevio/imu/preintegration.h"

namespace edgevio::estimator {

struct ExternalCheckResult {
  bool accepted = true;
  double rotation_deg = 0.0;   ///< angle between the link and the prediction
  double translation_m = 0.0;  ///< distance between the link's and the prediction's translations
};

ExternalCheckResult externalCheck(const geometry::SE3& T_nr_measured, const imu::NavState& r,
                                  const imu::NavState& predicted_n, const geometry::SE3& T_b_c,
                                  double max_rotation_deg, double max_translation_m);

}  // namespace edgevio::estimator
