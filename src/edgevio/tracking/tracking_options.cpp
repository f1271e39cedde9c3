// The options table of TrackingOptions (docs/configuration.md is generated from it).
#include "edgevio/tracking/tracking_options.h"

namespace edgevio::tracking {

EDGEVIO_OPTIONS_TABLE(TrackingOptions,
    number("keyframe_edge_ratio", &S::keyframe_edge_ratio, 2.0, "-",
           "new keyframe when the level-0 or level-1 edge counts of frame and keyframe differ by more than this factor", above(1)),
    number("keyframe_min_points", &S::keyframe_min_points, 100, "-", "new keyframe when the keyframe has fewer reference points",
           atLeast(0)),
    number("keyframe_min_visible_ratio", &S::keyframe_min_visible_ratio, 0.8, "-",
           "new keyframe when a smaller fraction of its reference points stays in view", closed(0, 1)),
    number("gyro_check_deg", &S::gyro_check_deg, 3.0, "deg",
           "an alignment this far in rotation from the predicted rotation is redone from the prediction on the fine levels",
           above(0)),
    number("gyro_check_realign_levels", &S::gyro_check_realign_levels, 2, "-",
           "pyramid levels of that re-alignment (and of the translation check's)", atLeast(1)),
    number("imu_translation_check_m", &S::imu_translation_check_m, 0.05, "m",
           "IMU modes: an alignment this far from the IMU's predicted translation is redone from the prediction on the fine "
           "levels; the fit closer to the edges is kept",
           above(0).orOff()),
    number("constant_velocity_max_accel_mps2", &S::constant_velocity_max_accel_mps2, 100.0, "m/s^2",
           "without a gyroscope reading (an IMU gap) a frame is predicted by the last two frames' motion, continued; an "
           "alignment further from that prediction than this acceleration over the interval reaches is redone from the "
           "prediction on the fine levels, and fails the self check if it stays beyond (10 g: no rig's motion, another basin)",
           above(0).orOff()),
    number("rotation_prior_deg", &S::rotation_prior_deg, 0.05, "deg",
           "IMU modes: std. dev. of the gyroscope's rotation since the keyframe as a prior of the alignment, for 1 px of edge "
           "noise",
           above(0).orOff()),
    number("rotation_prior_fraction", &S::rotation_prior_fraction, 0.015, "-",
           "... plus this fraction of that rotation's angle (gyroscope scale and timing errors)", atLeast(0)),
    number("lost_after_failures", &S::lost_after_failures, 10, "-",
           "this many consecutive self-check failures: the estimate is lost from the first of them until a frame tracks again "
           "(summary.json lost_intervals)",
           atLeast(1)),
    number("lost_gyro_disagreement_deg", &S::lost_gyro_disagreement_deg, 2.0, "deg",
           "the gyroscope contradicts a frame whose estimated rotation since the previous frame is this far from its own",
           above(0)),
    number("lost_gyro_contradictions", &S::lost_gyro_contradictions, 3, "-",
           "this many contradicted frames (in the visual modes: or frames failing the self check) among the last "
           "lost_after_failures: the estimate is lost from the first of them until a frame tracks uncontradicted with fewer "
           "left in that window (frozen, occluded or drifting images; 0: off)",
           atLeast(0)),
    number("lost_accel_mps2", &S::lost_accel_mps2, 1000.0, "m/s^2",
           "a pose whose step from the previous one implies an acceleration beyond this (100 g: no rig's motion, an "
           "alignment gone to another basin) is lost, until a frame tracks with a plausible one",
           above(0).orOff()),
    number("lost_speed_mps", &S::lost_speed_mps, 100.0, "m/s",
           "... or a step implying a speed beyond this (racing drones reach 40-50 m/s; an estimate running away at a steady "
           "speed has no large acceleration)",
           above(0).orOff()),
    number("lost_accel_disagreement_m", &S::lost_accel_disagreement_m, 0.1, "m",
           "a pose further than this (plus the next option's share) from where the accelerometer puts it, given the previous "
           "two poses, is lost until a frame tracks with a plausible step: a jump to another basin that every other check "
           "passes (0.1-0.6 m; edge noise moves a pose by millimetres, 2 ms of timestamp jitter in fast flight up to 0.1 m)",
           above(0).orOff()),
    number("lost_accel_disagreement_mps2", &S::lost_accel_disagreement_mps2, 1.0, "m/s^2",
           "... plus this acceleration's reach over the two intervals, a*dt*(dt+dt0)/2: the accelerometer's unknown bias and "
           "a few degrees of attitude error, which matter when frames are far apart",
           atLeast(0)),
    number("static_init_window_s", &S::static_init_window_s, 1.0, "s", "IMU window at the start used for static initialisation",
           above(0)),
    number("static_chunk_s", &S::static_chunk_s, 0.1, "s",
           "static initialisation judges motion on means over chunks this long (vibration averages out, motion does not)",
           above(0)),
    number("static_accel_std_max", &S::static_accel_std_max, 0.3, "m/s^2",
           "the start is static if the spread of the chunks' accelerometer means is below this", above(0)),
    number("static_gyro_std_max", &S::static_gyro_std_max, 0.03, "rad/s",
           "... and the spread of their gyroscope means below this", above(0)))

}  // namespace edgevio::tracking
