// The options table of EstimatorOptions (docs/configuration.md is generated from it).
#include "edgevio/estimator/estimator_options.h"

namespace edgevio::estimator {

EDGEVIO_OPTIONS_TABLE(EstimatorOptions,
    number("window_size", &S::window_size, 30, "-", "N: states kept in the sliding window", atLeast(3)),
    number("max_iterations", &S::max_iterations, 2, "-", "Gauss-Newton iterations per frame", atLeast(1)),
    number("realtime_pose_iterations", &S::realtime_pose_iterations, 0, "-",
           "--realtime: the frame's pose is handed out after this many of them (the rest follow it; offline all precede it); "
           "0: after the newest state alone is solved, the others held, and all of them follow",
           atLeast(0)),
    choice("coupling", &S::coupling, Coupling::kSemiTight, kCouplingChoices, "what a tracking link puts in the window"),
    number("tight_points", &S::tight_points, 1000, "-",
           "coupling tight: at most this many of a keyframe's level-0 reference points, evenly strided, are the window's",
           atLeast(1)),
    number("tight_pixel_sigma_px", &S::tight_pixel_sigma_px, 4.0, "px",
           "coupling tight: std. dev. of an edge residual (level-0 pixels, half the camera's resolution); larger than the "
           "edges' own error because neighbouring points' errors are correlated",
           above(0)),
    number("tight_huber_px", &S::tight_huber_px, 1.0, "px", "coupling tight: Huber threshold of an edge residual", above(0)),
    number("tight_disparity_sigma_px", &S::tight_disparity_sigma_px, 0.1, "px",
           "coupling tight: std. dev. of block matching's level-0 disparity, the prior of a point's inverse depth", above(0)),
    number("huber_translation_m", &S::huber_translation_m, 0.1, "m",
           "c_t of eq 24: Huber threshold of a visual link's translation error", above(0)),
    number("huber_rotation_deg", &S::huber_rotation_deg, 2.0, "deg",
           "c_a of eq 25: Huber threshold of a visual link's rotation error", above(0)),
    number("damping", &S::damping, 1e-9, "-", "first lambda of the perturbed Cholesky, relative to the largest diagonal entry",
           above(0)),
    number("external_check_rotation_deg", &S::external_check_rotation_deg, 1.0, "deg",
           "reject a tracking link this far in rotation from the IMU prediction (paper: 3)", above(0)),
    number("external_check_translation_m", &S::external_check_translation_m, 0.2, "m", "... or this far in translation", above(0)),
    number("loop_check_rotation_deg", &S::loop_check_rotation_deg, 1.0, "deg",
           "IMU modes: reject a loop or back link this far in rotation from the window's estimate of the same relative pose",
           above(0)),
    number("loop_check_translation_m", &S::loop_check_translation_m, 0.1, "m", "... or this far in translation", above(0)),
    number("front_translation_m", &S::front_translation_m, 0.3, "m",
           "front marginalisation when |dp|/this + angle/front_rotation_deg < 1 (the second-newest state against the keyframe)",
           above(0)),
    number("front_rotation_deg", &S::front_rotation_deg, 10.0, "deg", "rotation scale of that distance", above(0)),
    number("front_marginalization_drops_links", &S::front_marginalization_drops_links, false, "-",
           "front marginalisation folds the inertial links of the frame it removes into the prior and drops the visual "
           "links measured in it (VINS-Mono's choice): they share their keyframe's error with the links that stay, which "
           "the prior would otherwise take as independent information; false: it folds every link (METHOD.md §5)"),
    number("visual_covariance_scale", &S::visual_covariance_scale, 10.0, "-",
           "a visual link's covariance is the alignment's (J'WJ)^-1 times this", above(0)),
    number("visual_shared_fraction", &S::visual_shared_fraction, 0.0, "-",
           "the part of a visual link's covariance that every link from the same reference keyframe shares (its depth and "
           "edges): the window weighs those links jointly, as one error common to all plus one of each; 0: independent links",
           closed(0, 0.95)),
    number("imu_noise_inflation", &S::imu_noise_inflation, 5.0, "-",
           "the calibration's IMU white-noise densities are multiplied by this", above(0)),
    number("gyro_bias_walk_inflation", &S::gyro_bias_walk_inflation, 2.0, "-",
           "the calibration's gyroscope bias random walk is multiplied by this", above(0)),
    number("accel_bias_walk_inflation", &S::accel_bias_walk_inflation, 2.0, "-",
           "the calibration's accelerometer bias random walk is multiplied by this", above(0)),
    number("max_imu_gap_s", &S::max_imu_gap_s, 0.05, "s",
           "IMU readings further apart than this are a gap: no inertial link and no gyroscope rotation spans it (the edges carry "
           "the pose across; the window restarts when the IMU is back)", above(0)),
    number("repropagate_accel_bias", &S::repropagate_accel_bias, 0.05, "m/s^2",
           "an inertial link is integrated again when its linearisation accelerometer bias is this far off", above(0)),
    number("repropagate_gyro_bias", &S::repropagate_gyro_bias, 0.005, "rad/s", "... or its gyroscope bias this far", above(0)),
    number("init_tilt_sigma_deg", &S::init_tilt_sigma_deg, 1.0, "deg",
           "prior std. dev. of the first roll and pitch after a static start", above(0)),
    number("init_velocity_sigma", &S::init_velocity_sigma, 0.1, "m/s", "prior std. dev. of the first velocity after a static start",
           above(0)),
    number("init_accel_bias_sigma", &S::init_accel_bias_sigma, 0.2, "m/s^2", "prior std. dev. of the first accelerometer bias",
           above(0)),
    number("init_gyro_bias_sigma", &S::init_gyro_bias_sigma, 0.01, "rad/s",
           "prior std. dev. of the first gyroscope bias after a static start (10x this without one)", above(0)),
    number("reset_accel_bias", &S::reset_accel_bias, 2.0, "m/s^2", "an accelerometer bias estimate beyond this restarts the window",
           above(0)),
    number("reset_gyro_bias", &S::reset_gyro_bias, 0.3, "rad/s", "a gyroscope bias estimate beyond this restarts the window",
           above(0)),
    number("reset_velocity", &S::reset_velocity, 50.0, "m/s", "a speed estimate beyond this restarts the window", above(0)),
    number("gauge_prior", &S::gauge_prior, true, "-",
           "hold the oldest state's position and yaw by a stiff zero-residual prior (false: move the states back after each "
           "step, METHOD.md §5)"),
    number("first_estimate_jacobians", &S::first_estimate_jacobians, true, "-",
           "take the Jacobians of the states in the marginalisation prior at its linearisation point (false: at the estimate, "
           "the paper's)"),
    number("estimate_time_offset", &S::estimate_time_offset, false, "-",
           "IMU modes: estimate the camera-IMU time offset (IMU time minus camera time) in the window, starting from the "
           "input's stamps (frames.csv time_offset_ms)"),
    number("time_offset_sigma_ms", &S::time_offset_sigma_ms, 10.0, "ms",
           "prior std. dev. of that offset around zero", above(0)),
    number("estimate_cam_imu_rotation", &S::estimate_cam_imu_rotation, false, "-",
           "IMU modes: estimate a correction of the calibration's camera-IMU rotation in the window (frames.csv "
           "cam_imu_rotation_correction_deg)"),
    number("cam_imu_rotation_sigma_deg", &S::cam_imu_rotation_sigma_deg, 2.0, "deg",
           "prior std. dev. of that correction's angle about each axis", above(0)),
    number("estimate_cam_imu_translation", &S::estimate_cam_imu_translation, false, "-",
           "IMU modes: estimate a correction of the calibration's camera-IMU translation (the lever arm) in the window "
           "(frames.csv cam_imu_translation_correction_m); it needs rotation about more than one axis to be observable"),
    number("cam_imu_translation_sigma_m", &S::cam_imu_translation_sigma_m, 0.02, "m",
           "prior std. dev. of that correction along each axis", above(0)),
    Rule<S>{[](const S& s) {
              return s.coupling != Coupling::kTight ||
                     !(s.estimate_time_offset || s.estimate_cam_imu_rotation || s.estimate_cam_imu_translation);
            },
            "coupling: tight does not estimate the camera-IMU calibration (estimate_time_offset, estimate_cam_imu_rotation, "
            "estimate_cam_imu_translation must be false)"})

}  // namespace edgevio::estimator
