// The options tables of SimOptions and its SceneOptions (docs/configuration.md is generated from them).
#include "edgevio/sim/sim_options.h"

namespace edgevio::sim {

EDGEVIO_OPTIONS_TABLE(SceneOptions,
    number("room_margin_m", &S::room_margin_m, 2.5, "m", "free space between the path's bounding box and the walls", above(0)),
    number("floor_below_path_m", &S::floor_below_path_m, 1.0, "m", "floor distance below the lowest point of the path", above(0)),
    number("ceiling_above_path_m", &S::ceiling_above_path_m, 1.2, "m", "ceiling distance above the highest point of the path",
           above(0)),
    number("min_room_size_m", &S::min_room_size_m, 7.0, "m", "smallest horizontal room dimension", above(0)),
    number("max_room_size_m", &S::max_room_size_m, 80.0, "m", "a path needing a larger room is rejected (texture detail would be lost)",
           above(0)),
    number("obstacle_count", &S::obstacle_count, 10, "-", "obstacles (boxes, panels, pillars) to place; fewer if they do not fit",
           closed(0, 200)),
    number("obstacle_clearance_m", &S::obstacle_clearance_m, 1.0, "m", "minimum distance between an obstacle and the path",
           atLeast(0)),
    number("texture_log2_size", &S::texture_log2_size, 10, "-", "textures have 2^n x 2^n texels", closed(6, 12)),
    number("texture_tile_m", &S::texture_tile_m, 4.0, "m", "a texture tile covers this many metres", above(0)),
    number("texture_dir", &S::texture_dir, "", "-", "optional folder of PNG/JPG images used as wall textures"))

EDGEVIO_OPTIONS_TABLE(SimOptions,
    number("knot_dt_s", &S::knot_dt_s, 0.01, "s",
           "spline control-point spacing, never below a trajectory file's median sample spacing (wider smooths away motion "
           "a replayed real IMU measured)",
           closed(0.005, 0.5)),
    number("max_trajectory_gap_s", &S::max_trajectory_gap_s, 0.1, "s", "a longer gap in a trajectory file is an error", above(0)),
    number("trajectory_max_accel_mps2", &S::trajectory_max_accel_mps2, 50.0, "m/s^2",
           "a trajectory file's position step (a tracker glitch) is removed where a sample's velocity differs from its "
           "neighbours' median by more than this x dt",
           above(0).orOff()),
    number("trajectory_step_spread_s", &S::trajectory_step_spread_s, 1.0, "s",
           "a removed step's offset comes back as a ramp this long, so the motion follows the file in the long run", above(0)),
    number("static_start_s", &S::static_start_s, 1.0, "s", "standstill at the start of every built-in scenario", atLeast(0)),
    number("scenario_duration_s", &S::scenario_duration_s, 30.0, "s", "scenario length when --duration is not given", above(0)),
    nested(&S::scene, SceneOptions::table()),
    number("exposure_gain", &S::exposure_gain, 0.7, "-", "radiance to image scale (0.7: a typical wall near mid-grey)", above(0)),
    number("image_noise_sigma", &S::image_noise_sigma, 2.0, "DN", "sensor read noise (with --noise on)", atLeast(0)),
    number("vignetting", &S::vignetting, 0.2, "-", "brightness loss at the image corners (V = 1 - k r^2)", halfOpen(0, 1)),
    number("stereo_brightness_mismatch", &S::stereo_brightness_mismatch, 0.04, "-", "right camera gain = left gain x (1 + this)"),
    number("exposure_drift_amplitude", &S::exposure_drift_amplitude, 0.25, "-",
           "auto-exposure gain drift, fraction (with --exposure-changes)", halfOpen(0, 1)),
    number("exposure_drift_period_s", &S::exposure_drift_period_s, 6.0, "s", "period of the auto-exposure drift", above(0)),
    number("lighting_change_interval_s", &S::lighting_change_interval_s, 3.0, "s", "mean time between sudden lighting changes",
           above(0)),
    number("lighting_change_magnitude", &S::lighting_change_magnitude, 0.5, "-",
           "a lighting change scales the lights by [1-m, 1+m]", halfOpen(0, 1)),
    number("blur_substep_ms", &S::blur_substep_ms, 2.0, "ms", "time between sub-frames integrated for motion blur", above(0)),
    number("initial_gyro_bias_sigma", &S::initial_gyro_bias_sigma, 0.003, "rad/s", "std. dev. of the initial gyroscope bias",
           atLeast(0)),
    number("initial_accel_bias_sigma", &S::initial_accel_bias_sigma, 0.05, "m/s^2", "std. dev. of the initial accelerometer bias",
           atLeast(0)),
    number("imu_time_offset_ms", &S::imu_time_offset_ms, 0.0, "ms",
           "the IMU's clock minus the cameras': a reading taken at time t is stamped t + this (a rig whose clocks "
           "disagree; `edgevio doctor` measures it)",
           closed(-1000, 1000)),
    number("png_compression", &S::png_compression, 1, "-", "zlib level of the PNG files (speed against size)", closed(0, 9)),
    number("threads", &S::threads, 2, "-", "rendering threads (the output is the same for any value)", closed(1, 64)))

}  // namespace edgevio::sim
