// The options table of DatasetOptions (docs/configuration.md is generated from it).
#include "edgevio/io/dataset_options.h"

namespace edgevio::io {

EDGEVIO_OPTIONS_TABLE(DatasetOptions,
    number("stereo_sync_tolerance_s", &S::stereo_sync_tolerance_s, 0.003, "s",
           "largest |t_cam0 - t_cam1| for two images to form a stereo pair", halfOpen(0, 0.5)),
    number("imu_gap_warning_s", &S::imu_gap_warning_s, 0.025, "s", "an IMU gap longer than this is reported as a warning",
           above(0)),
    number("imu_glitch_gyro_rad_s", &S::imu_glitch_gyro_rad_s, 2.5, "rad/s",
           "a gyroscope reading this far (any axis) from the median of the five around it is a glitch, replaced by that median "
           "(real EuRoC logs: at most 1.2)",
           above(0).orOff()),
    number("imu_glitch_accel_mps2", &S::imu_glitch_accel_mps2, 40.0, "m/s^2",
           "... or an accelerometer reading this far (real EuRoC logs, landings included: at most 18)", above(0).orOff()),
    number("imu_time_offset_ms", &S::imu_time_offset_ms, 0.0, "ms",
           "the IMU's clock minus the cameras', beyond the calibration's (a Kalibr camchain's timeshift_cam_imu, applied "
           "already; `edgevio doctor` measures what is left): the IMU's stamps are moved back by this when read",
           closed(-1000, 1000)))

}  // namespace edgevio::io
