// The options table of DoctorOptions (docs/configuration.md is generated from it).
#include "edgevio/doctor/doctor_options.h"

namespace edgevio::doctor {

EDGEVIO_OPTIONS_TABLE(DoctorOptions,
    number("max_duration_s", &S::max_duration_s, 60.0, "s",
           "frames of the sequence's first this many seconds are aligned to each other (time offset, rotation, stereo)",
           above(0)),
    number("max_time_offset_ms", &S::max_time_offset_ms, 100.0, "ms", "the camera-IMU time offset is searched within +- this",
           closed(1, 1000)),
    number("min_rotation_rate_rad_s", &S::min_rotation_rate_rad_s, 0.1, "rad/s",
           "the time offset and the camera-IMU rotation need the rotation rate to vary by at least this (std. dev.) about "
           "two axes; below it they are reported as not observable",
           above(0)),
    number("standstill_min_s", &S::standstill_min_s, 1.0, "s", "shortest standstill the IMU's bias and noise are measured on",
           above(0)),
    number("standstill_gyro_std_rad_s", &S::standstill_gyro_std_rad_s, 0.02, "rad/s",
           "a standstill's gyroscope readings vary less than this (std. dev. per axis; EuRoC's MAV at rest with its motors "
           "running: 0.012-0.014, in flight 0.05-0.2)",
           above(0)),
    number("standstill_accel_std_mps2", &S::standstill_accel_std_mps2, 0.3, "m/s^2",
           "a standstill's accelerometer readings vary less than this (std. dev. per axis; EuRoC's MAV at rest: 0.2, in "
           "flight 0.6-1.5)",
           above(0)),
    number("time_offset_warning_ms", &S::time_offset_warning_ms, 3.0, "ms", "a larger camera-IMU time offset is a finding",
           above(0)),
    number("rotation_warning_deg", &S::rotation_warning_deg, 0.5, "deg",
           "a larger angle between the calibration's camera-IMU rotation and the measured one is a finding", above(0)),
    number("vertical_disparity_warning_px", &S::vertical_disparity_warning_px, 0.5, "px",
           "a larger median vertical disparity of rectified stereo matches is a finding", above(0)),
    number("noise_ratio_warning", &S::noise_ratio_warning, 3.0, "-",
           "a noise density measured at standstill more than this times above or below the sensor file's is a finding",
           above(1)),
    number("gravity_tolerance_mps2", &S::gravity_tolerance_mps2, 0.2, "m/s^2",
           "the accelerometer's magnitude at standstill further than this from 9.81 is a finding", above(0)),
    number("valid_depth_warning", &S::valid_depth_warning, 0.2, "-",
           "a smaller fraction of edge pixels with a stereo depth is a finding", closed(0, 1)),
    number("exposure_jump", &S::exposure_jump, 0.2, "-",
           "a frame whose mean brightness differs from its predecessor's by more than this fraction is an exposure change",
           above(0)),
    number("blur_ratio", &S::blur_ratio, 0.5, "-",
           "a frame whose edge sharpness is below this fraction of the sequence's median is blurred", halfOpen(0, 1)),
    number("clipped_pixels", &S::clipped_pixels, 0.25, "-",
           "a frame with more than this fraction of pixels at 255 (or at 0-5) is over- (or under-) exposed (EuRoC's "
           "V1 room, tracked well: 10 % at 255 from its lamps and windows)",
           halfOpen(0, 1)),
    number("clipped_frames_warning", &S::clipped_frames_warning, 0.05, "-",
           "more than this fraction of blurred, over- or under-exposed frames is a finding", closed(0, 1)),
    number("min_imu_rate_hz", &S::min_imu_rate_hz, 100.0, "Hz", "a slower IMU is a finding", above(0)),
    number("stereo_frames", &S::stereo_frames, 20, "-", "frames spread over the sequence whose stereo matches are checked",
           closed(1, 1000)))

}  // namespace edgevio::doctor
