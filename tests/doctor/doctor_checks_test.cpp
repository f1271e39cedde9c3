// The doctor's checks on signals whose answer is known: an IMU log with a
// standstill of known bias and noise, a gap and clipped readings; the
// camera's rotations along a scenario's motion against its synthesised IMU
// with the IMU's clock 15 ms late and a calibration 2 deg off.
#include "edgevio/doctor/doctor.h"

#include <gtest/gtest.h>

#include <opencv2/imgproc.hpp>

#include <cmath>
#include <random>

#include "common/imu_scenario.h"

namespace edgevio::doctor {
namespace {

using geometry::SO3;

constexpr double kDegToRad = M_PI / 180.0;
constexpr std::int64_t kImuDtNs = 5000000;  // 200 Hz

TEST(CheckImu, StandstillBiasNoiseGravityGapAndClipping) {
  // 3 s at rest (bias b, white noise of EuRoC's densities), then 3 s turning.
  const Vec3 bias(0.002, -0.021, 0.076);
  const double gyro_density = 1.6968e-4, accel_density = 2.0e-3, dt = 1e-9 * kImuDtNs;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n01;
  std::vector<imu::ImuSample> imu;
  for (std::int64_t t = 0; t < 6000000000LL; t += kImuDtNs) {
    imu::ImuSample s;
    s.t_ns = t;
    const double ts = 1e-9 * static_cast<double>(t);
    s.gyro = bias + gyro_density / std::sqrt(dt) * Vec3(n01(rng), n01(rng), n01(rng));
    s.accel = Vec3(0, 0, 9.81) + accel_density / std::sqrt(dt) * Vec3(n01(rng), n01(rng), n01(rng));
    if (ts >= 3.0) {
      s.gyro += Vec3(std::sin(3 * ts), std::cos(2 * ts), 0.5 * std::sin(ts));
      s.accel += Vec3(2 * std::sin(5 * ts), 0, 0);
    }
    imu.push_back(s);
  }
  // A 0.2 s gap at 4 s; five readings clipped at a value no other reaches.
  imu.erase(imu.begin() + 800, imu.begin() + 840);
  for (std::size_t k = 900; k < 905; ++k) imu[k].gyro.x() = 4.0;

  const DoctorOptions o;
  const ImuCheck c = checkImu(imu, 0.05, o);
  EXPECT_NEAR(c.rate_hz, 200.0, 1e-6);
  EXPECT_EQ(c.gaps, 1);
  EXPECT_NEAR(c.longest_gap_s, 0.205, 1e-9);
  EXPECT_EQ(c.saturated_samples, 5);
  // The standstill is found in half-windows of 0.5 s: all of [0, 3) s.
  EXPECT_NEAR(c.standstill_start_s, 0.0, 1e-9);
  EXPECT_NEAR(c.standstill_s, 3.0, 0.01);
  // Mean of N = 600 readings: standard error sigma_d / sqrt(N); 4 of them.
  const double bias_tolerance = 4 * gyro_density / std::sqrt(dt) / std::sqrt(600.0);
  EXPECT_LT((c.gyro_bias - bias).cwiseAbs().maxCoeff(), bias_tolerance);
  // A std. dev. from 3 x 600 readings has a relative standard error of 1/sqrt(2 x 1800): 1.7 %; 4 of them.
  EXPECT_NEAR(c.gyro_noise_density / gyro_density, 1.0, 0.07);
  EXPECT_NEAR(c.accel_noise_density / accel_density, 1.0, 0.07);
  EXPECT_NEAR(c.gravity_mps2, 9.81, 0.01);
}

TEST(CheckImu, NoStandstillWhileMoving) {
  std::vector<imu::ImuSample> imu;
  for (std::int64_t t = 0; t < 4000000000LL; t += kImuDtNs) {
    const double ts = 1e-9 * static_cast<double>(t);
    imu.push_back({t, Vec3(std::sin(3 * ts), 0, 0), Vec3(0, 0, 9.81)});
  }
  EXPECT_EQ(checkImu(imu, 0.05, DoctorOptions{}).standstill_s, 0.0);
}

/// The camera's rotations at 20 Hz along a scenario (from its spline, each
/// frame's attitude perturbed by `noise_deg`), its IMU stamped `offset_ms`
/// late, and the check against a calibration `calib_error_deg` off.
MotionCheck motionCheck(const std::string& scenario, std::uint64_t seed, double offset_ms, double calib_error_deg,
                        double noise_deg, int mistrack_every = 0) {
  const test::ImuScenario s(scenario, seed);
  const SO3 R_b_c = s.rig.T_b_c[0].so3();
  std::vector<imu::ImuSample> imu = s.imu.samples;
  for (imu::ImuSample& x : imu) x.t_ns += static_cast<std::int64_t>(std::llround(offset_ms * 1e6));
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> n01;
  const auto cameraAttitude = [&](std::int64_t t) {
    const Vec3 n(n01(rng), n01(rng), n01(rng));
    return s.pose(t).so3() * R_b_c * SO3::exp(noise_deg * kDegToRad * n);
  };
  std::vector<FrameRotation> rotations;
  const std::int64_t begin = s.spline.beginNs() + 1000000000LL, end = s.spline.endNs() - 1000000000LL;
  SO3 before = cameraAttitude(begin);
  for (std::int64_t t = begin + 50000000; t <= end; t += 50000000) {
    const SO3 now = cameraAttitude(t);
    rotations.push_back({t - 50000000, t, before.inverse() * now});
    // A mis-track: an alignment that stayed at its prediction (the motion
    // of the pair before) and passed its self check anyway.
    if (mistrack_every > 0 && rotations.size() % static_cast<std::size_t>(mistrack_every) == 0)
      rotations.back().R_c0_c1 = rotations[rotations.size() - 2].R_c0_c1;
    before = now;
  }
  const SO3 calibrated = R_b_c * SO3::exp(calib_error_deg * kDegToRad * Vec3(1, 1, 0).normalized());
  return checkMotion(rotations, imu, calibrated, 0.05, DoctorOptions{});
}

TEST(CheckMotion, FindsTheClockOffsetAndTheCalibrationsRotationError) {
  // Noise-free camera: only the IMU's own noise and the midpoint rule limit
  // it (seeds 21-30: offsets within 0.002 ms, angles within 0.0012 deg).
  const MotionCheck exact = motionCheck("aggressive", 21, 15.0, 2.0, 0.0);
  ASSERT_TRUE(exact.observable);
  EXPECT_NEAR(exact.time_offset_ms, 15.0, 0.01);
  EXPECT_NEAR(exact.rotation_error_deg, 2.0, 0.005);
  // With 0.02 deg of alignment noise per frame, seeds 21-30 gave offsets
  // within 0.014 ms of the truth with a reported sigma of 0.016-0.020 ms,
  // and angles within 0.009 deg: tolerances of about 3 of those spreads.
  for (std::uint64_t seed : {21, 22, 23}) {
    const MotionCheck m = motionCheck("aggressive", seed, 15.0, 2.0, 0.02);
    EXPECT_NEAR(m.time_offset_ms, 15.0, 0.05) << "seed " << seed;
    EXPECT_LT(std::abs(m.time_offset_ms - 15.0), 3 * m.time_offset_sigma_ms) << "seed " << seed;
    EXPECT_NEAR(m.rotation_error_deg, 2.0, 0.03) << "seed " << seed;
  }
}

TEST(CheckMotion, AlignmentsStuckAtTheirPredictionDoNotBiasIt) {
  // One pair in 10 repeats the pair before (an alignment that stayed at its
  // prediction): within the noise-only tolerances above.
  const MotionCheck m = motionCheck("aggressive", 21, 15.0, 2.0, 0.02, 10);
  ASSERT_TRUE(m.observable);
  EXPECT_NEAR(m.time_offset_ms, 15.0, 0.05);
  EXPECT_NEAR(m.rotation_error_deg, 2.0, 0.03);
}

TEST(CheckMotion, RotationAboutOneAxisIsNotObservable) {
  // Rate 0.5 sin(t) rad/s about the body's z axis only; camera = body.
  std::vector<imu::ImuSample> imu;
  for (std::int64_t t = 0; t <= 20000000000LL; t += kImuDtNs)
    imu.push_back({t, Vec3(0, 0, 0.5 * std::sin(1e-9 * static_cast<double>(t))), Vec3(0, 0, 9.81)});
  std::vector<FrameRotation> rotations;
  for (std::int64_t t = 1000000000LL; t < 19000000000LL; t += 50000000) {
    const double angle = 0.5 * (std::cos(1e-9 * static_cast<double>(t)) - std::cos(1e-9 * static_cast<double>(t + 50000000)));
    rotations.push_back({t, t + 50000000, SO3::exp(Vec3(0, 0, angle))});
  }
  const MotionCheck m = checkMotion(rotations, imu, SO3(), 0.05, DoctorOptions{});
  EXPECT_FALSE(m.observable);
  EXPECT_GT(m.rotation_rate_std_rad_s[0], 0.3);  // 0.5 / sqrt(2) about z
  EXPECT_LT(m.rotation_rate_std_rad_s[1], 1e-6);
}

TEST(EdgeSharpness, IsTheGreyStepPerPixelAcrossAnEdge) {
  // A sharp step of 100 grey levels: the central difference across it is
  // 100 over 2 px; a ramp of 25 per pixel: 25.
  cv::Mat sharp(32, 64, CV_8UC1, cv::Scalar(50)), ramp(32, 64, CV_8UC1, cv::Scalar(50));
  sharp.colRange(32, 64).setTo(150);
  for (int x = 30; x < 64; ++x) ramp.col(x).setTo(std::min(150, 50 + 25 * (x - 30)));
  cv::Mat edges(32, 64, CV_8UC1, cv::Scalar(0));
  edges(cv::Rect(31, 4, 1, 24)).setTo(255);
  EXPECT_NEAR(edgeSharpness(sharp, edges), 50.0, 1e-4);
  edges.setTo(0);
  edges(cv::Rect(32, 4, 1, 24)).setTo(255);
  EXPECT_NEAR(edgeSharpness(ramp, edges), 25.0, 1e-4);
  EXPECT_EQ(edgeSharpness(ramp, cv::Mat::zeros(32, 64, CV_8UC1)), 0.0);
}

TEST(VerticalDisparities, MeasureASubPixelRowShift) {
  // A smooth random texture; the right image is it 20 px to the left and
  // dy px down (bilinear).
  cv::Mat noise(240, 320, CV_8UC1), left;
  cv::randu(noise, 0, 256);
  cv::GaussianBlur(noise, left, cv::Size(0, 0), 2.0);
  cv::normalize(left, left, 0, 255, cv::NORM_MINMAX);
  for (double dy : {0.0, 0.4, -1.3}) {
    const cv::Mat M = (cv::Mat_<double>(2, 3) << 1, 0, -20, 0, 1, dy);
    cv::Mat right;
    cv::warpAffine(left, right, M, left.size(), cv::INTER_LINEAR, cv::BORDER_REFLECT);
    const std::vector<double> d = verticalDisparities(left, right, 64);
    ASSERT_GT(d.size(), 50u) << "dy " << dy;
    // The parabola's pixel locking: up to 0.006 px measured at 0, 0.4, -1.3.
    EXPECT_NEAR(median(d), dy, 0.02) << "dy " << dy;
  }
}

DoctorReport healthyReport() {
  DoctorReport r;
  r.imu.samples = 2000;
  r.imu.rate_hz = 200;
  r.images.frames = 200;
  r.images.rate_hz = 20;
  r.stereo.matches = 500;
  r.stereo.frames = 20;
  r.stereo.valid_depth_fraction = 0.7;
  r.motion.rotations = 199;
  r.motion.observable = true;
  r.motion.offset_cost = {1.0, 0.5, 1.0};
  return r;
}

TEST(FindFindings, HealthyDataHasNoWarningAndEachFaultItsFinding) {
  const camera::StereoRig rig;
  const DoctorOptions o;
  DoctorReport r = healthyReport();
  for (const Finding& f : findFindings(r, rig, 0.05, o)) EXPECT_EQ(f.severity, Severity::kInfo) << f.what;

  r.motion.time_offset_ms = 15.0;
  r.stereo.abs_vertical_disparity_px = r.stereo.vertical_disparity_px = 2.4;
  const std::vector<Finding> f = findFindings(r, rig, 0.05, o);
  ASSERT_GE(f.size(), 2u);
  // Most severe first; each names its evidence and a fix.
  EXPECT_EQ(f[0].severity, Severity::kError);
  EXPECT_EQ(f[1].severity, Severity::kError);
  EXPECT_NE(f[0].fix.find("dataset.imu_time_offset_ms"), std::string::npos) << f[0].fix;
  EXPECT_NE(f[1].what.find("2.40 px"), std::string::npos) << f[1].what;
}

}  // namespace
}  // namespace edgevio::doctor
