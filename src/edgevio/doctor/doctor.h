#pragma once
// `edgevio doctor`: what is wrong with a rig's data before any run. Each check
// is a function of plain data (the IMU log, the visual rotations between
// frames, image statistics), so that each can be tested on a signal whose
// answer is known; `diagnose` reads a sequence and calls them all, and
// `findFindings` turns the measurements into findings, each with its evidence
// and a fix.
#include <cstdint>
#include <functional>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "edgevio/camera/calibration.h"
#include "edgevio/doctor/doctor_options.h"
#include "edgevio/geometry/so3.h"
#include "edgevio/imu/imu_types.h"

namespace edgevio {
struct Config;
namespace io {
class Sequence;
}
}  // namespace edgevio

namespace edgevio::doctor {

/// The IMU log: rate, gaps, clipping, and the sensor at standstill.
struct ImuCheck {
  std::size_t samples = 0;
  double rate_hz = 0.0;              ///< from the median spacing
  int gaps = 0;                      ///< spacings longer than estimator.max_imu_gap_s
  double longest_gap_s = 0.0;
  int saturated_samples = 0;         ///< readings at a channel's extreme value that repeats (a clipped sensor)
  double standstill_s = 0.0;         ///< the longest standstill (0: none of doctor.standstill_min_s)
  double standstill_start_s = 0.0;   ///< its start, from the first reading
  Vec3 gyro_bias = Vec3::Zero();     ///< mean gyroscope reading at standstill [rad/s]
  double gyro_noise_density = 0.0;   ///< std. dev. x sqrt(1 / rate) at standstill [rad/s/sqrt(Hz)]
  double accel_noise_density = 0.0;  ///< [m/s^2/sqrt(Hz)]
  double gravity_mps2 = 0.0;         ///< mean accelerometer magnitude at standstill
};
ImuCheck checkImu(const std::vector<imu::ImuSample>& imu, double max_gap_s, const DoctorOptions& options);

/// The rotation of the (rectified left) camera between two frames, from
/// aligning them: R_{c(t0) c(t1)}.
struct FrameRotation {
  std::int64_t t0_ns = 0, t1_ns = 0;
  geometry::SO3 R_c0_c1;
};

/// The camera-IMU time offset and rotation from the frames' rotations
/// against the gyroscope's.
struct MotionCheck {
  std::size_t rotations = 0;         ///< frame pairs aligned
  std::size_t failed_alignments = 0;
  bool observable = false;           ///< rotation rate varied enough about two axes (doctor.min_rotation_rate_rad_s)
  double rotation_rate_std_rad_s[3] = {0, 0, 0};  ///< spread of the camera's rotation rate along its principal axes, largest first
  double time_offset_ms = 0.0;       ///< IMU time minus camera time
  double time_offset_sigma_ms = 0.0;
  std::vector<double> offsets_ms, offset_cost;  ///< the search: mean squared rate residual [(rad/s)^2] per offset
  geometry::SO3 R_b_c;               ///< measured camera-IMU rotation (rectified left camera in the body)
  double rotation_error_deg = 0.0;   ///< angle between it and the calibration's
  Vec3 gyro_bias = Vec3::Zero();     ///< gyroscope minus the camera's rate in the body frame [rad/s]
  double residual_rad_s = 0.0;       ///< RMS rate residual at the estimate
  std::vector<double> t_s, camera_rate, gyro_rate;  ///< rotation rates [rad/s] per frame pair, the gyro's at the offset
};
/// `R_b_c_calibrated`: the calibration's rotation of the camera the rotations are of.
MotionCheck checkMotion(const std::vector<FrameRotation>& rotations, const std::vector<imu::ImuSample>& imu,
                        const geometry::SO3& R_b_c_calibrated, double max_gap_s, const DoctorOptions& options);

/// Rectified stereo: vertical disparity of matched corners, depth coverage.
struct StereoCheck {
  std::size_t frames = 0, matches = 0;
  double vertical_disparity_px = 0.0;      ///< median of right y - left y
  double abs_vertical_disparity_px = 0.0;  ///< median of its magnitude
  double valid_depth_fraction = 0.0;       ///< level-0 edge pixels with a stereo depth, over the aligned frames
  std::vector<double> vertical_disparities;
};

/// The images: timing, exposure, blur, clipping.
struct ImageCheck {
  std::size_t frames = 0;
  double rate_hz = 0.0;  ///< from the median spacing
  int missing_frames = 0;  ///< frames a spacing longer than 1.5 x the median leaves out
  int exposure_changes = 0, blurred_frames = 0, overexposed_frames = 0, underexposed_frames = 0;
  std::vector<double> t_s, brightness, sharpness;  ///< per frame read: mean grey, mean gradient at edges
};

enum class Severity { kInfo, kWarning, kError };
inline constexpr options::Choice<Severity> kSeverityChoices[] = {
    {Severity::kInfo, "info", "worth knowing; nothing to fix"},
    {Severity::kWarning, "warning", "likely to cost accuracy"},
    {Severity::kError, "error", "likely to make a run drift or diverge"}};

struct Finding {
  Severity severity = Severity::kInfo;
  std::string what, evidence, fix;
};

struct DoctorReport {
  std::string dataset;
  double duration_s = 0.0;  ///< of the frames read
  ImuCheck imu;
  ImageCheck images;
  StereoCheck stereo;
  MotionCheck motion;
  std::vector<Finding> findings;
};

/// The findings the measurements support, most severe first.
std::vector<Finding> findFindings(const DoctorReport& report, const camera::StereoRig& rig, double max_gap_s,
                                  const DoctorOptions& options);

/// (frames done, frames to do).
using DoctorProgress = std::function<void(std::size_t, std::size_t)>;
/// Reads the sequence's first doctor.max_duration_s and runs every check.
DoctorReport diagnose(io::Sequence& sequence, const Config& config, const DoctorProgress& progress = {});

/// Mean grey-level step per pixel across the edge pixels (`edges` non-zero)
/// of an 8-bit image: blur spreads an edge's step over more pixels.
double edgeSharpness(const cv::Mat& image, const cv::Mat& edges);
/// Vertical disparities (right y - left y) of corners of a rectified left
/// image matched in the right one, within `max_disparity` px to the left
/// and 6 rows up or down: normalised cross-correlation of an 11x11 patch,
/// sub-pixel by a parabola across rows; kept when the correlation is over
/// 0.9 and clearly above the best match elsewhere (repetitive texture).
std::vector<double> verticalDisparities(const cv::Mat& left, const cv::Mat& right, int max_disparity);

/// The median of `values` (the upper middle one of an even count); 0 for none.
double median(std::vector<double> values);

void writeText(std::ostream& out, const DoctorReport& report);
void writeJson(std::ostream& out, const DoctorReport& report);
/// One HTML page: the verdict, the findings and SVG plots of the evidence.
std::string htmlPage(const DoctorReport& report);

}  // namespace edgevio::doctor
