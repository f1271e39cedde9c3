#pragma once
#include <string>

namespace edgevio::tracking {

/// Options of the keyframe policy and the edge tracker (config section `tracking`; METHOD.md §3).
struct TrackingOptions {
  double keyframe_edge_ratio = 2.0;          ///< new keyframe when level-0/1 edge counts differ by more than this factor [-]
  int keyframe_min_points = 100;             ///< new keyframe when the keyframe has fewer reference points [-]
  double keyframe_min_visible_ratio = 0.8;   ///< new keyframe when fewer of its points remain visible [-]
  std::string translation_prior = "previous";  ///< initial translation: previous (paper) | constant_velocity
  double gyro_check_deg = 3.0;               ///< alignment rotation vs gyro prediction; larger: re-align from the prediction [deg]
  int gyro_check_realign_levels = 2;         ///< levels used when re-aligning after a failed gyro or translation check [-]
  double imu_translation_check_m = 0.05;     ///< alignment translation vs the IMU prediction; farther: re-align from the prediction on fine levels; 0: off [m]
  double rotation_prior_deg = 0.05;          ///< IMU modes: std. dev. of the gyroscope's rotation since the keyframe, as an alignment prior (per level-0 px of edge noise); 0: off [deg]
  double rotation_prior_fraction = 0.015;    ///< ... plus this fraction of the rotation angle (gyro scale, timing) [-]
  int lost_after_failures = 10;              ///< this many consecutive self-check failures: the run is lost [-]
  double static_init_window_s = 1.0;         ///< IMU window at the start used for static initialisation [s]
  double static_accel_std_max = 0.3;         ///< static if the spread of 0.1 s accelerometer means is below this [m/s²]
  double static_gyro_std_max = 0.03;         ///< ... and the spread of 0.1 s gyro means below this [rad/s]

  template <class Visitor>
  void visit(Visitor& v) {
    v("keyframe_edge_ratio", keyframe_edge_ratio, "-", "new keyframe when level-0/1 edge counts differ by more than this factor");
    v("keyframe_min_points", keyframe_min_points, "-", "new keyframe when the keyframe has fewer reference points");
    v("keyframe_min_visible_ratio", keyframe_min_visible_ratio, "-", "new keyframe when fewer of its points stay in view");
    v("translation_prior", translation_prior, "-", "initial translation of an alignment: previous (paper) | constant_velocity");
    v("gyro_check_deg", gyro_check_deg, "deg", "alignment vs gyro rotation; larger: re-align from the prediction on fine levels");
    v("gyro_check_realign_levels", gyro_check_realign_levels, "-", "pyramid levels used for that re-alignment (and the translation check's)");
    v("imu_translation_check_m", imu_translation_check_m, "m", "alignment vs IMU-predicted translation; farther: re-align from the prediction on fine levels, keep the closer fit (0: off)");
    v("rotation_prior_deg", rotation_prior_deg, "deg", "IMU modes: std. dev. of the gyroscope's rotation since the keyframe as a prior of the alignment, for 1 px of edge noise (0: off)");
    v("rotation_prior_fraction", rotation_prior_fraction, "-", "... plus this fraction of that rotation's angle");
    v("lost_after_failures", lost_after_failures, "-", "consecutive self-check failures after which the run counts as lost");
    v("static_init_window_s", static_init_window_s, "s", "IMU window at the start used for static initialisation");
    v("static_accel_std_max", static_accel_std_max, "m/s^2", "static if the spread of 0.1 s accelerometer means is below this");
    v("static_gyro_std_max", static_gyro_std_max, "rad/s", "static if the spread of 0.1 s gyro means is below this");
  }
  std::string validate() const;
};

}  // namespace edgevio::tracking
