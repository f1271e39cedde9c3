#include "edgevio/io/calibration_io.h"

#include <gtest/gtest.h>

#include <algorithm>

#include "common/mini_dataset.h"
#include "common/test_support.h"
#include "edgevio/common/error.h"

namespace edgevio::io {
namespace {

using test::TempDir;

// A Kalibr camchain describing the EuRoC rig (T_cam_imu = inverse of EuRoC's T_BS).
std::string kalibrCamchain(const camera::StereoRig& rig) {
  std::ostringstream o;
  o.precision(17);
  for (int i = 0; i < 2; ++i) {
    const Mat4 T = rig.T_b_c[i].inverse().matrix();
    o << "cam" << i << ":\n  T_cam_imu:\n";
    for (int r = 0; r < 4; ++r) o << "  - [" << T(r, 0) << ", " << T(r, 1) << ", " << T(r, 2) << ", " << T(r, 3) << "]\n";
    const auto& c = rig.cam[i];
    o << "  camera_model: pinhole\n  distortion_coeffs: [" << c.coeffs[0] << ", " << c.coeffs[1] << ", "
      << c.coeffs[2] << ", " << c.coeffs[3] << "]\n  distortion_model: radtan\n  intrinsics: [" << c.fx << ", "
      << c.fy << ", " << c.cx << ", " << c.cy << "]\n  resolution: [" << c.width << ", " << c.height
      << "]\n  rostopic: /cam" << i << "/image_raw\n";
  }
  return o.str();
}

TEST(CalibrationIo, EurocSensorYamlWithOpenCvHeader) {
  TempDir dir;
  const std::string root = test::writeMiniDataset(dir, {});
  const camera::StereoRig rig = loadCalibration(root);
  EXPECT_EQ(rig.cam[0].width, 64);
  EXPECT_EQ(rig.cam[0].distortion, camera::Distortion::kRadialTangential);
  EXPECT_NEAR(rig.cam[0].coeffs[0], -0.28340811, 1e-15);
  EXPECT_NEAR(rig.imu.gyro_noise_density, 1.6968e-4, 1e-18);
  EXPECT_NEAR(rig.imu.rate_hz, 200.0, 0.0);
  // EuRoC baseline is about 11 cm along the camera x axis.
  EXPECT_NEAR(rig.T_c0_c1().translation().norm(), 0.110, 0.002);
}

TEST(CalibrationIo, KalibrAgreesWithEuroc) {
  TempDir dir;
  const std::string root = test::writeMiniDataset(dir, {});
  const camera::StereoRig euroc = loadCalibration(root);
  const std::string camchain = dir.write("kalibr/camchain-imucam.yaml", kalibrCamchain(euroc));
  dir.write("kalibr/imu.yaml",
            "imu0:\n  accelerometer_noise_density: 0.002\n  accelerometer_random_walk: 0.003\n"
            "  gyroscope_noise_density: 0.00016968\n  gyroscope_random_walk: 1.9393e-05\n"
            "  rostopic: /imu0\n  update_rate: 200.0\n");
  const camera::StereoRig kalibr = loadCalibration(camchain);
  for (int i = 0; i < 2; ++i) {
    EXPECT_LT((kalibr.T_b_c[i].matrix() - euroc.T_b_c[i].matrix()).norm(), 1e-9);
    EXPECT_NEAR(kalibr.cam[i].fx, euroc.cam[i].fx, 1e-12);
    EXPECT_NEAR(kalibr.cam[i].coeffs[3], euroc.cam[i].coeffs[3], 1e-15);
  }
  EXPECT_NEAR(kalibr.imu.accel_random_walk, 0.003, 1e-15);
  EXPECT_EQ(kalibr.imu_time_offset_s, 0.0);  // no timeshift_cam_imu: none
}

TEST(CalibrationIo, KalibrTimeshiftIsTheImuClockOffsetAndRoundTrips) {
  TempDir dir;
  camera::StereoRig rig = eurocDefaultRig();
  rig.imu_time_offset_s = -0.0125;
  const std::string camchain = dir.file("camchain-imucam.yaml"), imu = dir.file("imu.yaml");
  writeKalibrCalibration(camchain, imu, rig);
  EXPECT_EQ(loadKalibrCalibration(camchain, imu).imu_time_offset_s, -0.0125);
  EXPECT_TRUE(loadKalibrCalibration(camchain, imu).warnings.empty());  // both cameras' shifts alike
  // Out of range: an error naming the file and line.
  std::string text = test::readFile(camchain);
  text.replace(text.find("timeshift_cam_imu: -0.0125"), 26, "timeshift_cam_imu: 3.5");
  dir.write("bad/camchain-imucam.yaml", text);
  try {
    loadKalibrCalibration(dir.file("bad/camchain-imucam.yaml"));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("timeshift_cam_imu"), std::string::npos) << e.what();
  }
  // The right camera 2 ms off the left: cam0's shift is used, with a warning
  // naming the file, cam1's line and the difference.
  text = test::readFile(camchain);
  text.replace(text.rfind("timeshift_cam_imu: -0.0125"), 26, "timeshift_cam_imu: -0.0105");
  dir.write("skew/camchain-imucam.yaml", text);
  const camera::StereoRig skewed = loadKalibrCalibration(dir.file("skew/camchain-imucam.yaml"));
  EXPECT_EQ(skewed.imu_time_offset_s, -0.0125);
  ASSERT_EQ(skewed.warnings.size(), 1u);
  const std::size_t line = 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(text.rfind("timeshift")), '\n'));
  EXPECT_NE(skewed.warnings[0].find("camchain-imucam.yaml:" + std::to_string(line) + ": cam1"), std::string::npos) << skewed.warnings[0];
  EXPECT_NE(skewed.warnings[0].find("by 2.0 ms"), std::string::npos) << skewed.warnings[0];
  // A shift for cam0 only (a hand-written file): cam0's, and nothing said of cam1.
  text = test::readFile(camchain);
  const std::size_t cam1_shift = text.rfind("  timeshift_cam_imu:");
  text.erase(cam1_shift, text.find('\n', cam1_shift) + 1 - cam1_shift);
  dir.write("cam0-only/camchain-imucam.yaml", text);
  const camera::StereoRig cam0_only = loadKalibrCalibration(dir.file("cam0-only/camchain-imucam.yaml"));
  EXPECT_EQ(cam0_only.imu_time_offset_s, -0.0125);
  EXPECT_TRUE(cam0_only.warnings.empty());
}

TEST(CalibrationIo, EquidistantModelIsRead) {
  TempDir dir;
  const std::string root = test::writeMiniDataset(dir, {});
  for (int cam = 0; cam < 2; ++cam) {
    std::string y = test::eurocCameraYaml(cam, 64, 48);
    y.replace(y.find("radial-tangential"), 17, "equidistant");
    dir.write("mav0/cam" + std::to_string(cam) + "/sensor.yaml", y);
  }
  EXPECT_EQ(loadCalibration(root).cam[1].distortion, camera::Distortion::kEquidistant);
}

TEST(CalibrationIo, HostileYamlIsAnErrorWithLine) {
  const std::string good = test::eurocCameraYaml(0, 64, 48);
  const std::vector<std::pair<std::string, std::string>> cases = {
      {good.substr(0, good.size() / 2), ""},  // truncated mid-matrix: a parse error or a missing key
      {"%YAML:1.0\n[unclosed\n", "invalid YAML"},
      {"just a scalar\n", "mapping"},
      {"", "mapping"},
      {"\x89PNG\x0d\x0a\x1a\x0a\x00\x00\x00", ""},
      {std::string(good).replace(good.find("intrinsics: ["), 13, "intrinsics: [x"), "expected a finite number"},
      {std::string(good).replace(good.find("resolution: ["), 13, "resolution: [1, 2, 3, "), "list of 2 numbers"},
      {std::string(good).replace(good.find("camera_model: pinhole"), 21, "camera_model: omni"), "not supported"},
      {std::string(good).replace(good.find("radial-tangential"), 17, "fov"), "distortion_model 'fov'"},
      {std::string(good).replace(good.find("0.0148655429818"), 15, "5.0"), "not a rigid transform"},
      {std::string(good).replace(good.find("rows: 4"), 7, "rows: 3"), "4x4"},
      {std::string(good).replace(good.find("intrinsics: ["), 13, "intrinsics: [-"), "focal"},
  };
  for (const auto& [text, fragment] : cases) {
    TempDir dir;
    const std::string root = test::writeMiniDataset(dir, {});
    const std::string p = dir.write("mav0/cam0/sensor.yaml", text);
    SCOPED_TRACE(text);
    test::expectInputError([&] { loadCalibration(root); }, {p, fragment});
  }
}

TEST(CalibrationIo, RealEurocCalibration) {
  EDGEVIO_REQUIRE_SHARED_DATA("euroc/V1_01_easy_micro");
  const camera::StereoRig rig = loadCalibration(data_path);
  EXPECT_EQ(rig.cam[1].width, 752);
  EXPECT_DOUBLE_EQ(rig.cam[1].fx, 457.587);
  EXPECT_NEAR(rig.T_c0_c1().translation().norm(), 0.1101, 0.0005);
}

}  // namespace
}  // namespace edgevio::io
