// The doctor's findings and its three outputs: text, JSON, an HTML page.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <sstream>

#include "edgevio/common/format.h"
#include "edgevio/common/json.h"
#include "edgevio/doctor/doctor.h"
#include "edgevio/eval/svg_plot.h"

namespace edgevio::doctor {

namespace {

constexpr double kStandardGravity = 9.81;



}  // namespace

std::vector<Finding> findFindings(const DoctorReport& r, const camera::StereoRig& rig, double max_gap_s,
                                  const DoctorOptions& o) {
  std::vector<Finding> f;
  const auto add = [&](Severity s, std::string what, std::string evidence, std::string fix) {
    f.push_back({s, std::move(what), std::move(evidence), std::move(fix)});
  };

  // Camera against IMU.
  const MotionCheck& m = r.motion;
  if (!m.observable) {
    add(Severity::kWarning, "camera-IMU time offset and rotation not measured",
        formatText("%.0f frame pairs aligned; the camera's rotation rate varied by %.3f and %.3f rad/s about its two main axes "
               "(doctor.min_rotation_rate_rad_s = %.2f)",
               static_cast<double>(m.rotations), m.rotation_rate_std_rad_s[0], m.rotation_rate_std_rad_s[1],
               o.min_rotation_rate_rad_s),
        "record a few seconds of rotation about every axis (turn the rig by hand), or run the doctor on a sequence in motion");
  } else {
    const double offset = std::abs(m.time_offset_ms);
    if (offset > o.time_offset_warning_ms)
      add(offset > 3 * o.time_offset_warning_ms ? Severity::kError : Severity::kWarning,
          formatText("camera and IMU clocks disagree by %.1f ms", m.time_offset_ms),
          formatText("the gyroscope's rate matches the camera's best with the IMU's stamps %.1f +- %.1f ms late (mean squared "
                 "rate residual %.3g (rad/s)^2 there, %.3g at 0 ms)",
                 m.time_offset_ms, m.time_offset_sigma_ms,
                 *std::min_element(m.offset_cost.begin(), m.offset_cost.end()),
                 m.offset_cost.empty() ? 0.0 : m.offset_cost[m.offset_cost.size() / 2]),
          formatText("set dataset.imu_time_offset_ms to %.1f more than it is now (or Kalibr's timeshift_cam_imu to %.4f s "
                 "more), or fix the driver's time stamping; if it drifts, let the window follow it "
                 "(estimator.estimate_time_offset: true)",
                 m.time_offset_ms, m.time_offset_ms * 1e-3));
    if (m.rotation_error_deg > o.rotation_warning_deg) {
      const Quat q = m.R_b_c.quaternion();
      add(m.rotation_error_deg > 4 * o.rotation_warning_deg ? Severity::kError : Severity::kWarning,
          formatText("the calibration's camera-IMU rotation is %.2f deg off", m.rotation_error_deg),
          formatText("the camera's rotations between frames match the gyroscope's through a rotation %.2f deg from the "
                 "calibration's (rate residual %.3f rad/s RMS over %.0f frame pairs)",
                 m.rotation_error_deg, m.residual_rad_s, static_cast<double>(m.rotations)),
          formatText("recalibrate camera and IMU (Kalibr's kalibr_calibrate_imu_camera), or let the window correct it "
                 "(estimator.estimate_cam_imu_rotation: true); the measured rotation of the rectified "
                 "left camera in the body, as a quaternion w x y z: %.5f %.5f %.5f %.5f",
                 q.w(), q.x(), q.y(), q.z()));
    }
  }

  // The IMU.
  const ImuCheck& imu = r.imu;
  if (imu.rate_hz < o.min_imu_rate_hz)
    add(Severity::kWarning, formatText("the IMU runs at %.0f Hz", imu.rate_hz),
        formatText("median spacing of %.0f readings (doctor.min_imu_rate_hz = %.0f)", static_cast<double>(imu.samples),
               o.min_imu_rate_hz),
        "configure the IMU for 200 Hz or more: fast rotation between readings is integrated less accurately");
  if (imu.gaps > 0)
    add(Severity::kWarning, formatText("%d gaps in the IMU log", imu.gaps),
        formatText("spacings over estimator.max_imu_gap_s = %.3f s, the longest %.3f s", max_gap_s, imu.longest_gap_s),
        "check the IMU driver and its bus (USB bandwidth, queue sizes); the IMU modes restart their window after each gap");
  if (imu.saturated_samples > 0)
    add(Severity::kWarning, formatText("%d IMU readings clipped", imu.saturated_samples),
        "readings that sit at their channel's extreme value several times: the sensor's range was exceeded",
        "raise the gyroscope's or accelerometer's range in the driver");
  if (imu.standstill_s <= 0) {
    add(Severity::kInfo, "no standstill in the IMU log",
        formatText("no %.1f s without motion (gyroscope std. dev. under %.3f rad/s, accelerometer under %.2f m/s^2)",
               o.standstill_min_s, o.standstill_gyro_std_rad_s, o.standstill_accel_std_mps2),
        "start recordings with two seconds at rest: the IMU's bias and noise are then measured, and runs start from a static "
        "initialisation");
  } else {
    const auto noiseFinding = [&](const char* sensor, double measured, double file, const char* key, const char* unit) {
      const double ratio = measured / file;
      if (ratio > o.noise_ratio_warning || ratio < 1.0 / o.noise_ratio_warning)
        add(Severity::kWarning, std::string("the ") + sensor + "'s noise differs from the sensor file's",
            formatText("measured %.3g ", measured) + unit + formatText(" at standstill (%.1f s from %.1f s), the file says %.3g (x%.2f)",
                                                                imu.standstill_s, imu.standstill_start_s, file, ratio),
            std::string("set ") + key + formatText(" to %.3g in imu0/sensor.yaml or Kalibr's imu.yaml (motors running at rest "
                                               "add vibration: measure with them off)",
                                               measured));
    };
    noiseFinding("gyroscope", imu.gyro_noise_density, rig.imu.gyro_noise_density, "gyroscope_noise_density", "rad/s/sqrt(Hz)");
    noiseFinding("accelerometer", imu.accel_noise_density, rig.imu.accel_noise_density, "accelerometer_noise_density",
                 "m/s^2/sqrt(Hz)");
    if (std::abs(imu.gravity_mps2 - kStandardGravity) > o.gravity_tolerance_mps2)
      add(Severity::kError, formatText("the accelerometer reads %.2f m/s^2 at rest", imu.gravity_mps2),
          formatText("mean magnitude over %.1f s of standstill; gravity is %.2f", imu.standstill_s, kStandardGravity),
          "check the accelerometer's unit (g or m/s^2) and scale in the driver");
    add(Severity::kInfo, formatText("gyroscope bias %.4f rad/s at rest", imu.gyro_bias.norm()),
        formatText("mean reading over %.1f s of standstill: %.4f %.4f %.4f rad/s", imu.standstill_s, imu.gyro_bias.x(),
               imu.gyro_bias.y(), imu.gyro_bias.z()),
        "nothing: the estimator starts from this bias after a static start");
  }

  // Stereo.
  const StereoCheck& st = r.stereo;
  if (st.matches < 20) {
    add(Severity::kWarning, "stereo rectification not checked",
        formatText("%.0f corners matched between the rectified images of %.0f frames", static_cast<double>(st.matches),
               static_cast<double>(st.frames)),
        "check that the right images show the same scene, and the calibration's baseline and rotation");
  } else if (st.abs_vertical_disparity_px > o.vertical_disparity_warning_px) {
    add(st.abs_vertical_disparity_px > 3 * o.vertical_disparity_warning_px ? Severity::kError : Severity::kWarning,
        formatText("rectified stereo rows disagree by %.2f px", st.vertical_disparity_px),
        formatText("median vertical disparity %.2f px (median magnitude %.2f) over %.0f matched corners of %.0f frames",
               st.vertical_disparity_px, st.abs_vertical_disparity_px, static_cast<double>(st.matches),
               static_cast<double>(st.frames)),
        "recalibrate the stereo pair: the right camera's rotation or either camera's intrinsics are off");
  }
  if (st.valid_depth_fraction < o.valid_depth_warning)
    add(Severity::kWarning, formatText("only %.0f %% of edge pixels have a stereo depth", 100 * st.valid_depth_fraction),
        "level-0 edge pixels with a block-matching disparity, over every frame read",
        "check the stereo calibration (above) and vision.stereo_num_disparities (near objects need a larger range)");

  // Images.
  const ImageCheck& im = r.images;
  const double frames = std::max<double>(1, static_cast<double>(im.frames));
  if (im.missing_frames > 0)
    add(im.missing_frames > o.clipped_frames_warning * frames ? Severity::kWarning : Severity::kInfo,
        formatText("%d frames missing", im.missing_frames),
        formatText("frame spacings over 1.5 x the median (%.1f Hz)", im.rate_hz),
        "check the camera driver and the recorder's bandwidth (compressed images, a faster disk)");
  const auto frameFinding = [&](int count, const char* what, const std::string& evidence, const char* fix) {
    if (count > o.clipped_frames_warning * frames)
      add(Severity::kWarning, formatText("%.0f %% of the frames ", 100.0 * count / frames) + what, evidence, fix);
  };
  frameFinding(im.blurred_frames, "are blurred",
               formatText("edge sharpness under %.2f x the median (%.1f grey/px)", o.blur_ratio,
                      im.sharpness.empty() ? 0.0 : im.sharpness[im.sharpness.size() / 2]),
               "shorten the exposure time (cap auto-exposure), add light");
  frameFinding(im.overexposed_frames, "are overexposed",
               formatText("over %.0f %% of their pixels at 255", 100 * o.clipped_pixels),
               "lower the exposure or gain (auto-exposure target)");
  frameFinding(im.underexposed_frames, "are underexposed",
               formatText("over %.0f %% of their pixels at 5 or less", 100 * o.clipped_pixels),
               "raise the exposure or gain, add light");
  frameFinding(im.exposure_changes, "change brightness suddenly",
               formatText("mean grey level over %.0f %% from the previous frame", 100 * o.exposure_jump),
               "slow down auto-exposure, or fix the exposure");
  if (m.failed_alignments > o.clipped_frames_warning * frames)
    add(Severity::kWarning, formatText("%.0f frames could not be aligned to their predecessor", static_cast<double>(m.failed_alignments)),
        "the front end's self check refused the alignment without an IMU prediction",
        "see the image findings; fast motion needs a higher frame rate or shorter exposure");

  std::stable_sort(f.begin(), f.end(), [](const Finding& a, const Finding& b) { return a.severity > b.severity; });
  return f;
}

namespace {

std::string verdict(const DoctorReport& r) {
  int errors = 0, warnings = 0;
  for (const Finding& f : r.findings) {
    errors += f.severity == Severity::kError;
    warnings += f.severity == Severity::kWarning;
  }
  if (errors + warnings == 0) return "nothing wrong found";
  return formatText("%d error(s), %d warning(s)", errors, warnings);
}

}  // namespace

void writeText(std::ostream& out, const DoctorReport& r) {
  out << "edgevio doctor: " << r.dataset << "\n";
  out << formatText("  images   %.0f frames read (%.1f s) at %.1f Hz, %d missing\n", static_cast<double>(r.images.frames),
                    r.duration_s, r.images.rate_hz, r.images.missing_frames);
  out << formatText("  imu      %.0f readings at %.1f Hz, %d gaps, standstill %.1f s\n", static_cast<double>(r.imu.samples),
                    r.imu.rate_hz, r.imu.gaps, r.imu.standstill_s);
  if (r.motion.observable)
    out << formatText("  motion   time offset %.2f +- %.2f ms (IMU minus camera), camera-IMU rotation %.2f deg from the "
                  "calibration's\n",
                  r.motion.time_offset_ms, r.motion.time_offset_sigma_ms, r.motion.rotation_error_deg);
  else
    out << "  motion   too little rotation to measure the time offset and rotation\n";
  out << formatText("  stereo   vertical disparity %.2f px (median of %.0f matches), %.0f %% of edge pixels with depth\n",
                r.stereo.vertical_disparity_px, static_cast<double>(r.stereo.matches), 100 * r.stereo.valid_depth_fraction);
  for (const Finding& f : r.findings) {
    out << "\n" << options::nameOf(kSeverityChoices, f.severity) << ": " << f.what << "\n";
    out << "  evidence: " << f.evidence << "\n  fix: " << f.fix << "\n";
  }
  out << "\nverdict: " << verdict(r) << "\n";
}

void writeJson(std::ostream& out, const DoctorReport& r) {
  JsonWriter j(out);
  const auto vec = [&](const Vec3& v) {
    j.beginArray();
    for (int i = 0; i < 3; ++i) j.value(v[i]);
    j.endArray();
  };
  const bool motion = r.motion.observable;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  j.beginObject();
  j.key("dataset").value(r.dataset);
  j.key("verdict").value(verdict(r));
  j.key("time_offset_ms").value(motion ? r.motion.time_offset_ms : nan);
  j.key("time_offset_sigma_ms").value(motion ? r.motion.time_offset_sigma_ms : nan);
  j.key("cam_imu_rotation_error_deg").value(motion ? r.motion.rotation_error_deg : nan);
  j.key("stereo_vertical_disparity_px").value(r.stereo.matches > 0 ? r.stereo.vertical_disparity_px : nan);
  j.key("gyro_bias_rad_s");
  if (r.imu.standstill_s > 0) vec(r.imu.gyro_bias);
  else if (motion) vec(r.motion.gyro_bias);
  else j.null();
  j.key("gyro_bias_source").value(r.imu.standstill_s > 0 ? "standstill" : motion ? "motion" : "none");
  j.key("findings").beginArray();
  for (const Finding& f : r.findings) {
    j.beginObject();
    j.key("severity").value(options::nameOf(kSeverityChoices, f.severity));
    j.key("what").value(f.what).key("evidence").value(f.evidence).key("fix").value(f.fix);
    j.endObject();
  }
  j.endArray();
  j.key("images").beginObject();
  j.key("frames").value(r.images.frames).key("duration_s").value(r.duration_s).key("rate_hz").value(r.images.rate_hz);
  j.key("missing_frames").value(r.images.missing_frames).key("exposure_changes").value(r.images.exposure_changes);
  j.key("blurred_frames").value(r.images.blurred_frames).key("overexposed_frames").value(r.images.overexposed_frames);
  j.key("underexposed_frames").value(r.images.underexposed_frames);
  j.endObject();
  j.key("imu").beginObject();
  j.key("samples").value(r.imu.samples).key("rate_hz").value(r.imu.rate_hz).key("gaps").value(r.imu.gaps);
  j.key("longest_gap_s").value(r.imu.longest_gap_s).key("saturated_samples").value(r.imu.saturated_samples);
  j.key("standstill_s").value(r.imu.standstill_s);
  j.key("gyro_noise_density").value(r.imu.standstill_s > 0 ? r.imu.gyro_noise_density : nan);
  j.key("accel_noise_density").value(r.imu.standstill_s > 0 ? r.imu.accel_noise_density : nan);
  j.key("gravity_mps2").value(r.imu.standstill_s > 0 ? r.imu.gravity_mps2 : nan);
  j.endObject();
  j.key("motion").beginObject();
  j.key("frame_pairs").value(r.motion.rotations).key("failed_alignments").value(r.motion.failed_alignments);
  j.key("observable").value(motion);
  j.key("rotation_rate_std_rad_s").beginArray();
  for (double s : r.motion.rotation_rate_std_rad_s) j.value(s);
  j.endArray();
  j.key("rate_residual_rad_s").value(r.motion.residual_rad_s);
  j.endObject();
  j.key("stereo").beginObject();
  j.key("frames").value(r.stereo.frames).key("matches").value(r.stereo.matches);
  j.key("abs_vertical_disparity_px").value(r.stereo.abs_vertical_disparity_px);
  j.key("valid_depth_fraction").value(r.stereo.valid_depth_fraction);
  j.endObject();
  j.endObject();
  out << "\n";
}

std::string htmlPage(const DoctorReport& r) {
  std::ostringstream o;
  o << "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>edgevio doctor</title>\n"
    << "<style>body{font-family:sans-serif;max-width:800px;margin:2em auto}td,th{padding:4px 8px;text-align:left;"
       "vertical-align:top}.error{color:#c92a2a}.warning{color:#e67700}.info{color:#495057}</style></head><body>\n";
  o << "<h1>edgevio doctor</h1>\n<p>" << eval::escapeXml(r.dataset) << "</p>\n<h2>Verdict: " << eval::escapeXml(verdict(r)) << "</h2>\n";
  o << "<table><tr><th>severity</th><th>finding</th><th>evidence</th><th>fix</th></tr>\n";
  for (const Finding& f : r.findings) {
    const char* s = options::nameOf(kSeverityChoices, f.severity);
    o << "<tr class='" << s << "'><td>" << s << "</td><td>" << eval::escapeXml(f.what) << "</td><td>" << eval::escapeXml(f.evidence)
      << "</td><td>" << eval::escapeXml(f.fix) << "</td></tr>\n";
  }
  o << "</table>\n<h2>Evidence</h2>\n";
  const MotionCheck& m = r.motion;
  if (!m.offset_cost.empty()) {
    o << eval::svgLineChart("Camera against gyroscope: rate residual over the time offset", "IMU time minus camera time [ms]",
                            "mean squared residual [(rad/s)^2]", {{"residual", "#d9480f", m.offsets_ms, m.offset_cost}},
                            m.time_offset_ms);
    o << eval::svgLineChart("Rotation rate at that offset", "time [s]", "rate [rad/s]",
                            {{"camera (edge alignment)", "#222222", m.t_s, m.camera_rate},
                             {"gyroscope - bias", "#d9480f", m.t_s, m.gyro_rate}});
  }
  if (!r.stereo.vertical_disparities.empty()) {
    // Histogram of the vertical disparities in 0.1 px bins.
    std::vector<double> bins, counts;
    for (int b = -30; b <= 30; ++b) {
      bins.push_back(0.1 * b);
      counts.push_back(0);
    }
    for (double d : r.stereo.vertical_disparities) {
      const long b = std::lround(d * 10) + 30;
      if (b >= 0 && b < static_cast<long>(counts.size())) counts[static_cast<std::size_t>(b)] += 1;
    }
    o << eval::svgLineChart("Stereo: vertical disparity of matched corners (0 when rectified right)", "right y - left y [px]",
                            "matches", {{"matches per 0.1 px", "#1c7ed6", bins, counts}}, 0.0);
  }
  if (!r.images.t_s.empty())
    o << eval::svgLineChart("Images: brightness and edge sharpness", "time [s]", "grey level, grey/px",
                            {{"mean grey", "#222222", r.images.t_s, r.images.brightness},
                             {"edge sharpness", "#2b8a3e", r.images.t_s, r.images.sharpness}});
  o << "</body></html>\n";
  return o.str();
}

}  // namespace edgevio::doctor
