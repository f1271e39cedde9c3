// trajectory_imu_rate_tum.txt (pipeline/imu_rate_output.h), offline and in
// real time, on a level body accelerating at a constant rate: its readings
// integrate exactly, so every pose written lies on the true parabola
// whichever estimate it was propagated from (the file's 9 decimals: 1e-8 m).
// The real-time case runs a thread (the thread-sanitizer stage runs it).
#include "edgevio/pipeline/imu_rate_output.h"

#include <gtest/gtest.h>

#include <thread>

#include "common/test_support.h"
#include "edgevio/io/trajectory_io.h"

namespace edgevio::pipeline {
namespace {

constexpr std::int64_t kImuStepNs = 5000000, kFrameStepNs = 50000000;  // 200 Hz, 20 Hz

const Vec3 kA(1.5, -0.5, 0.25), kV0(2.0, 0.0, -1.0);

imu::NavState truth(std::int64_t t_ns) {
  const double t = t_ns * 1e-9;
  imu::NavState x;
  x.p_w = kV0 * t + 0.5 * kA * t * t;
  x.v_w = kV0 + kA * t;
  return x;
}

std::vector<imu::ImuSample> readings(double seconds) {
  std::vector<imu::ImuSample> v;
  for (std::int64_t t = 0; t <= static_cast<std::int64_t>(seconds * 1e9); t += kImuStepNs) {
    imu::ImuSample s;
    s.t_ns = t;
    s.accel = kA + imu::gravity();
    v.push_back(s);
  }
  return v;
}

/// Every pose of the file on the truth; returns how many.
std::size_t checkPoses(const std::string& path) {
  const io::Trajectory poses = io::readTrajectory(path);
  for (const io::TrajectorySample& s : poses)
    EXPECT_LT((s.T_w_b.translation() - truth(s.t_ns).p_w).norm(), 1e-8) << s.t_ns;
  return poses.size();
}

TEST(ImuRateOutput, OfflineEveryReadingAfterTheFirstFrameUpToTheLastHasAPose) {
  const test::TempDir dir;
  const std::vector<imu::ImuSample> imu = readings(1.0);
  const std::string path = dir.path() + "/imu_rate.txt";
  const std::int64_t first = 2 * kImuStepNs, last = first + 15 * kFrameStepNs;
  std::size_t poses = 0;
  {
    ImuRateOutput out(imu, 0.05, path, false, first, ImuRateOutput::Clock::now());
    for (std::int64_t t = first; t <= last; t += kFrameStepNs) out.publish(t, truth(t));
    EXPECT_TRUE(out.finish(last).empty()) << "no latencies offline";
    poses = out.poses();
  }
  // Readings after the first frame up to the last: (last - first) / 5 ms of them.
  EXPECT_EQ(poses, static_cast<std::size_t>((last - first) / kImuStepNs));
  EXPECT_EQ(checkPoses(path), poses);
}

TEST(ImuRateOutput, WithATimeOffsetPosesAreWrittenAtCameraTimes) {
  // The IMU's clock 15 ms ahead: the reading taken at camera time t is stamped t + 15 ms.
  constexpr std::int64_t kOffsetNs = 15000000;
  const test::TempDir dir;
  std::vector<imu::ImuSample> imu = readings(1.0);
  for (imu::ImuSample& s : imu) s.t_ns += kOffsetNs;
  const std::string path = dir.path() + "/imu_rate.txt";
  const std::int64_t first = 2 * kImuStepNs, last = first + 15 * kFrameStepNs;
  {
    ImuRateOutput out(imu, 0.05, path, false, first, ImuRateOutput::Clock::now());
    for (std::int64_t t = first; t <= last; t += kFrameStepNs) out.publish(t, truth(t), kOffsetNs);
    out.finish(last);
  }
  const io::Trajectory poses = io::readTrajectory(path);
  ASSERT_FALSE(poses.empty());
  EXPECT_EQ(checkPoses(path), poses.size());
  EXPECT_LE(poses.back().t_ns, last);
}

TEST(ImuRateOutput, AnOffsetEstimateThatGrowsKeepsTheTimesIncreasing) {
  const test::TempDir dir;
  const std::vector<imu::ImuSample> imu = readings(1.0);
  const std::string path = dir.path() + "/imu_rate.txt";
  const std::int64_t first = 2 * kImuStepNs, last = first + 15 * kFrameStepNs;
  {
    ImuRateOutput out(imu, 0.05, path, false, first, ImuRateOutput::Clock::now());
    std::int64_t offset = 0;
    for (std::int64_t t = first; t <= last; t += kFrameStepNs, offset += 7 * kImuStepNs) out.publish(t, truth(t), offset);
    out.finish(last);
  }
  const io::Trajectory poses = io::readTrajectory(path);  // throws on a decreasing time
  EXPECT_GT(poses.size(), 10u);
}

TEST(ImuRateOutput, InRealTimeEachPoseHasItsLatency) {
  const test::TempDir dir;
  const std::vector<imu::ImuSample> imu = readings(0.5);
  const std::string path = dir.path() + "/imu_rate.txt";
  const auto start = ImuRateOutput::Clock::now();
  std::vector<double> latencies;
  std::size_t poses = 0;
  {
    ImuRateOutput out(imu, 0.05, path, true, 0, start);
    // Frames published as a tracking thread would, each some time after its own time.
    for (std::int64_t t = 0; t <= 8 * kFrameStepNs; t += kFrameStepNs) {
      std::this_thread::sleep_until(start + std::chrono::nanoseconds(t + kFrameStepNs / 2));
      out.publish(t, truth(t));
    }
    latencies = out.finish(8 * kFrameStepNs);
    poses = out.poses();
  }
  EXPECT_GT(poses, 0u);
  EXPECT_LE(poses, imu.size());
  EXPECT_EQ(latencies.size(), poses);
  for (double ms : latencies) EXPECT_GE(ms, 0.0);
  EXPECT_EQ(checkPoses(path), poses);
}

TEST(ImuRateOutput, StoppedBeforeAnyEstimateItWritesNothing) {
  const test::TempDir dir;
  const std::vector<imu::ImuSample> imu = readings(0.2);
  ImuRateOutput out(imu, 0.05, dir.path() + "/imu_rate.txt", true, 0, ImuRateOutput::Clock::now());
  EXPECT_TRUE(out.finish(0).empty());
  EXPECT_EQ(out.poses(), 0u);
}

}  // namespace
}  // namespace edgevio::pipeline
