#pragma once
#include <string>

#include "edgevio/sim/scene.h"

namespace edgevio::sim {

/// Options of the simulator (config section `sim`). Command-line flags of
/// `edgevio simulate` override the ones they name.
struct SimOptions {
  double knot_dt_s = 0.01;               ///< spline control-point spacing, at least the file's sample spacing [s]
  double max_trajectory_gap_s = 0.1;     ///< longer gaps in a trajectory file are errors [s]
  double trajectory_max_accel_mps2 = 50.0;  ///< a file's position step: a velocity this far·Δt from its neighbours' [m/s²]
  double trajectory_step_spread_s = 1.0;    ///< a removed step is restored as a ramp this long [s]
  double static_start_s = 1.0;           ///< standstill at the start of every scenario [s]
  double scenario_duration_s = 30.0;     ///< scenario length when --duration is not given [s]
  SceneOptions scene;
  double exposure_gain = 0.7;            ///< radiance → image scale; 0.7 puts a typical wall near mid-grey [-]
  double image_noise_sigma = 2.0;        ///< sensor read noise [DN]
  double vignetting = 0.2;               ///< brightness loss at the image corners [-]
  double stereo_brightness_mismatch = 0.04;  ///< right camera gain = left · (1 + this) [-]
  double exposure_drift_amplitude = 0.25;    ///< auto-exposure gain varies by ± this fraction [-]
  double exposure_drift_period_s = 6.0;      ///< period of the auto-exposure drift [s]
  double lighting_change_interval_s = 3.0;   ///< mean time between sudden lighting changes [s]
  double lighting_change_magnitude = 0.5;    ///< a change scales the lights by [1−m, 1+m] [-]
  double blur_substep_ms = 2.0;              ///< time between sub-frames integrated for motion blur [ms]
  double initial_gyro_bias_sigma = 0.003;    ///< std. dev. of the initial gyro bias [rad/s]
  double initial_accel_bias_sigma = 0.05;    ///< std. dev. of the initial accelerometer bias [m/s²]
  int png_compression = 1;                   ///< zlib level 0-9 of the PNG files (speed vs size) [-]
  int threads = 2;                           ///< rendering threads (output is identical for any value) [-]

  template <class Visitor>
  void visit(Visitor& v) {
    v("knot_dt_s", knot_dt_s, "s",
      "spline control-point spacing, never below a trajectory file's median sample spacing (wider smooths away motion a replayed real IMU measured: 0.05 keeps 67 % of a 5 Hz shake)");
    v("max_trajectory_gap_s", max_trajectory_gap_s, "s", "a longer gap in a trajectory file is an error");
    v("trajectory_max_accel_mps2", trajectory_max_accel_mps2, "m/s^2",
      "a trajectory file's position step (tracker glitch) is removed where a sample's velocity differs from its neighbours' median by more than this x dt (0: keep the file as is)");
    v("trajectory_step_spread_s", trajectory_step_spread_s, "s", "a removed step's offset comes back as a ramp this long, so the motion follows the file in the long run");
    v("static_start_s", static_start_s, "s", "standstill at the start of every built-in scenario");
    v("scenario_duration_s", scenario_duration_s, "s", "scenario length when --duration is not given");
    v("room_margin_m", scene.room_margin_m, "m", "free space between the path's bounding box and the walls");
    v("floor_below_path_m", scene.floor_below_path_m, "m", "floor distance below the lowest point of the path");
    v("ceiling_above_path_m", scene.ceiling_above_path_m, "m", "ceiling distance above the highest point of the path");
    v("min_room_size_m", scene.min_room_size_m, "m", "smallest horizontal room dimension");
    v("max_room_size_m", scene.max_room_size_m, "m", "a path needing a larger room is rejected");
    v("obstacle_count", scene.obstacle_count, "-", "obstacles (boxes, panels, pillars) to place");
    v("obstacle_clearance_m", scene.obstacle_clearance_m, "m", "minimum distance between obstacles and the path");
    v("texture_log2_size", scene.texture_log2_size, "-", "textures have 2^n x 2^n texels");
    v("texture_tile_m", scene.texture_tile_m, "m", "a texture tile covers this many metres");
    v("texture_dir", scene.texture_dir, "-", "optional folder of PNG/JPG images used as wall textures");
    v("exposure_gain", exposure_gain, "-", "radiance to image scale (0.7: a typical wall near mid-grey)");
    v("image_noise_sigma", image_noise_sigma, "DN", "sensor read noise (with --noise on)");
    v("vignetting", vignetting, "-", "brightness loss at the image corners (V = 1 - k r^2)");
    v("stereo_brightness_mismatch", stereo_brightness_mismatch, "-", "right camera gain = left gain x (1 + this)");
    v("exposure_drift_amplitude", exposure_drift_amplitude, "-", "auto-exposure gain drift, fraction (with --exposure-changes)");
    v("exposure_drift_period_s", exposure_drift_period_s, "s", "period of the auto-exposure drift");
    v("lighting_change_interval_s", lighting_change_interval_s, "s", "mean time between sudden lighting changes");
    v("lighting_change_magnitude", lighting_change_magnitude, "-", "a lighting change scales the lights by [1-m, 1+m]");
    v("blur_substep_ms", blur_substep_ms, "ms", "time between sub-frames integrated for motion blur");
    v("initial_gyro_bias_sigma", initial_gyro_bias_sigma, "rad/s", "std. dev. of the initial gyro bias (with noise)");
    v("initial_accel_bias_sigma", initial_accel_bias_sigma, "m/s^2", "std. dev. of the initial accelerometer bias");
    v("png_compression", png_compression, "-", "PNG compression level 0-9 (speed vs size)");
    v("threads", threads, "-", "rendering threads (output is identical for any value)");
  }
  std::string validate() const;
};

}  // namespace edgevio::sim
