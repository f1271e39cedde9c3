// IMU glitches: a spiked reading is replaced, real motion is not.
#include "edgevio/imu/imu_glitches.h"

#include <gtest/gtest.h>

#include <cmath>

#include "common/test_support.h"
#include "edgevio/io/dataset_options.h"
#include "edgevio/io/imu_io.h"

namespace edgevio::imu {
namespace {

/// 1 s at 200 Hz of a fast sinusoidal motion: 8 rad/s and 30 m/s^2 at 3 Hz.
std::vector<ImuSample> motion() {
  std::vector<ImuSample> v;
  for (int i = 0; i < 200; ++i) {
    const double t = 0.005 * i, w = 2 * kPi * 3;
    v.push_back({i * 5000000LL, Vec3(8 * std::sin(w * t), 0.1, 0), Vec3(30 * std::cos(w * t), 0, 9.81)});
  }
  return v;
}

TEST(ImuGlitches, ASpikedReadingIsReplacedByItsNeighboursMedian) {
  const std::vector<ImuSample> truth = motion();
  std::vector<ImuSample> imu = truth;
  imu[57].gyro += Vec3::Constant(3.0);
  imu[120].accel.z() += 50.0;
  const std::vector<std::size_t> replaced = replaceGlitches(&imu, 2.5, 40.0);
  ASSERT_EQ(replaced, (std::vector<std::size_t>{57, 120}));
  // The median of five samples of a smooth motion is within the motion's
  // change over two readings: 8 rad/s x 2pi x 3 Hz x 10 ms = 1.5 rad/s at most.
  EXPECT_LT((imu[57].gyro - truth[57].gyro).norm(), 1.6);
  EXPECT_LT((imu[120].accel - truth[120].accel).norm(), 30 * 2 * kPi * 3 * 0.01);
  for (std::size_t i = 0; i < imu.size(); ++i) {
    if (i != 57 && i != 120) {
      EXPECT_EQ(imu[i].gyro, truth[i].gyro) << i;
    }
  }
}

TEST(ImuGlitches, FastRealMotionIsNotAGlitch) {
  std::vector<ImuSample> imu = motion();
  EXPECT_TRUE(replaceGlitches(&imu, 2.5, 40.0).empty());
  EXPECT_TRUE(replaceGlitches(&imu, 0.0, 0.0).empty());  // both tests off
  // Across a 0.3 s gap the motion changed by far more than a glitch's size:
  // the readings beside it are not compared with the ones beyond.
  std::vector<ImuSample> gappy;
  for (const ImuSample& s : motion())
    if (s.t_ns < 400000000 || s.t_ns >= 700000000) gappy.push_back(s);
  EXPECT_TRUE(replaceGlitches(&gappy, 2.5, 40.0).empty());
}

TEST(ImuGlitches, RealEurocLogsHaveNoneAtTheDefaults) {
  // The six real EuRoC logs (takeoffs, landings and MH's vibration included)
  // deviate from their median-of-five by at most 1.16 rad/s and 18 m/s^2.
  EDGEVIO_REQUIRE_SHARED_DATA("trajectories/euroc");
  const io::DatasetOptions o;
  for (const char* seq : {"MH_03_medium", "MH_04_difficult", "V1_01_easy", "V1_02_medium", "V2_01_easy", "V2_02_medium"}) {
    std::vector<ImuSample> imu = io::readImuCsv(data_path + "/" + seq + "/imu0.csv", 1.0, nullptr);
    EXPECT_TRUE(replaceGlitches(&imu, o.imu_glitch_gyro_rad_s, o.imu_glitch_accel_mps2).empty()) << seq;
  }
}

}  // namespace
}  // namespace edgevio::imu
