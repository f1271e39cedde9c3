#pragma once
#include <string>

#include "edgevio/estimator/sliding_window.h"

namespace edgevio::estimator {

/// Options of the sliding-window estimator (config section `estimator`; METHOD.md §4, §5).
struct EstimatorOptions {
  int window_size = 30;                       ///< N: states kept in the window [-]
  int max_iterations = 2;                     ///< Gauss-Newton iterations per frame [-]
  double huber_translation_m = 0.1;           ///< c_t of eq 24 [m]
  double huber_rotation_deg = 2.0;            ///< c_a of eq 25 [deg]
  double damping = 1e-9;                      ///< first λ of the perturbed Cholesky, relative to the largest diagonal entry [-]
  double external_check_rotation_deg = 1.0;   ///< reject a tracking link this far in rotation from the IMU prediction (paper: 3) [deg]
  double external_check_translation_m = 0.2;  ///< ... or this far in translation [m]
  double loop_check_rotation_deg = 1.0;       ///< reject a loop link this far in rotation from the window's estimate of it [deg]
  double loop_check_translation_m = 0.1;      ///< ... or this far in translation [m]
  double front_translation_m = 0.3;           ///< front marginalisation when ‖Δp‖/this + angle/front_rotation_deg < 1 [m]
  double front_rotation_deg = 10.0;           ///< (distance of the second-newest state to the keyframe) [deg]
  double visual_covariance_scale = 10.0;      ///< a tracking link's covariance is the alignment's (JᵀWJ)⁻¹ times this [-]
  double imu_noise_inflation = 5.0;           ///< IMU white-noise densities from the calibration times this [-]
  double gyro_bias_walk_inflation = 2.0;      ///< the gyroscope's bias random walk from the calibration times this [-]
  double accel_bias_walk_inflation = 2.0;     ///< the accelerometer's bias random walk from the calibration times this [-]
  double max_imu_gap_s = 0.05;                ///< IMU readings further apart than this break the inertial chain (restart) [s]
  double repropagate_accel_bias = 0.05;       ///< re-integrate a link when its linearisation b_a is this far off [m/s²]
  double repropagate_gyro_bias = 0.005;       ///< ... or its b_g [rad/s]
  double init_tilt_sigma_deg = 1.0;           ///< prior std. dev. of the first roll and pitch after a static start [deg]
  double init_velocity_sigma = 0.1;           ///< prior std. dev. of the first velocity after a static start [m/s]
  double init_accel_bias_sigma = 0.2;         ///< prior std. dev. of the first accelerometer bias [m/s²]
  double init_gyro_bias_sigma = 0.01;         ///< prior std. dev. of the first gyro bias (after static init) [rad/s]
  double reset_accel_bias = 2.0;              ///< an accelerometer bias estimate beyond this resets the estimator [m/s²]
  double reset_gyro_bias = 0.3;               ///< a gyro bias estimate beyond this resets the estimator [rad/s]
  double reset_velocity = 50.0;               ///< a speed beyond this resets the estimator [m/s]
  bool gauge_prior = true;                    ///< gauge by a stiff prior on the oldest position and yaw instead of re-anchoring
  bool first_estimate_jacobians = true;       ///< Jacobians of prior states at the prior's linearisation point (FEJ)

  template <class Visitor>
  void visit(Visitor& v) {
    v("window_size", window_size, "-", "N: states kept in the sliding window");
    v("max_iterations", max_iterations, "-", "Gauss-Newton iterations per frame");
    v("huber_translation_m", huber_translation_m, "m", "c_t of eq 24: Huber threshold of a visual link's translation error");
    v("huber_rotation_deg", huber_rotation_deg, "deg", "c_a of eq 25: Huber threshold of a visual link's rotation error");
    v("damping", damping, "-", "first lambda of the perturbed Cholesky, relative to the largest diagonal entry");
    v("external_check_rotation_deg", external_check_rotation_deg, "deg", "reject a tracking link this far in rotation from the IMU prediction (paper: 3)");
    v("external_check_translation_m", external_check_translation_m, "m", "... or this far in translation");
    v("loop_check_rotation_deg", loop_check_rotation_deg, "deg", "IMU modes: reject a loop link this far in rotation from the window's estimate of the same relative pose");
    v("loop_check_translation_m", loop_check_translation_m, "m", "... or this far in translation");
    v("front_translation_m", front_translation_m, "m", "front marginalisation when |dp|/this + angle/front_rotation_deg < 1 (second-newest vs keyframe)");
    v("front_rotation_deg", front_rotation_deg, "deg", "rotation scale of that distance");
    v("visual_covariance_scale", visual_covariance_scale, "-", "tracking-link covariance = alignment (J'WJ)^-1 times this");
    v("imu_noise_inflation", imu_noise_inflation, "-", "IMU white-noise densities from the calibration are multiplied by this");
    v("gyro_bias_walk_inflation", gyro_bias_walk_inflation, "-", "the gyroscope's bias random walk from the calibration is multiplied by this");
    v("accel_bias_walk_inflation", accel_bias_walk_inflation, "-", "the accelerometer's bias random walk from the calibration is multiplied by this");
    v("max_imu_gap_s", max_imu_gap_s, "s", "IMU readings further apart than this break the inertial chain (the estimator restarts)");
    v("repropagate_accel_bias", repropagate_accel_bias, "m/s^2", "re-integrate an inertial link when its linearisation b_a is this far off");
    v("repropagate_gyro_bias", repropagate_gyro_bias, "rad/s", "... or its b_g");
    v("init_tilt_sigma_deg", init_tilt_sigma_deg, "deg", "prior std. dev. of the first roll and pitch after a static start");
    v("init_velocity_sigma", init_velocity_sigma, "m/s", "prior std. dev. of the first velocity after a static start");
    v("init_accel_bias_sigma", init_accel_bias_sigma, "m/s^2", "prior std. dev. of the first accelerometer bias");
    v("init_gyro_bias_sigma", init_gyro_bias_sigma, "rad/s", "prior std. dev. of the first gyro bias (after static initialisation)");
    v("reset_accel_bias", reset_accel_bias, "m/s^2", "an accelerometer bias estimate beyond this resets the estimator");
    v("reset_gyro_bias", reset_gyro_bias, "rad/s", "a gyro bias estimate beyond this resets the estimator");
    v("reset_velocity", reset_velocity, "m/s", "a speed estimate beyond this resets the estimator");
    v("gauge_prior", gauge_prior, "-", "gauge by a stiff prior on the oldest state's position and yaw instead of moving the states after each step");
    v("first_estimate_jacobians", first_estimate_jacobians, "-", "Jacobians of the states in the marginalisation prior at its linearisation point (first-estimate Jacobians)");
  }
  std::string validate() const;
  SolverOptions solver() const {
    SolverOptions s;
    s.max_iterations = max_iterations;
    s.huber_translation_m = huber_translation_m;
    s.huber_rotation_deg = huber_rotation_deg;
    s.damping = damping;
    s.gauge_prior = gauge_prior;
    s.first_estimate_jacobians = first_estimate_jacobians;
    return s;
  }
};

}  // namespace edgevio::estimator
