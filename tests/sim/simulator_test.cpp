// The simulator: clear errors for bad requests, motion that follows the
// trajectory file's. (Whole folders: simulator_e2e_test.cpp.)
#include "edgevio/sim/simulator.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/sim_fixture.h"
#include "common/test_support.h"
#include "edgevio/common/error.h"
#include "edgevio/geometry/types.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/io/imu_io.h"
#include "edgevio/io/trajectory_io.h"

namespace edgevio::sim {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

TEST(Simulator, BadInputIsExplained) {
  TempDir dir;
  const auto expectError = [&](SimRequest r, const std::string& fragment) {
    test::expectInputError([&] { simulate(r, test::fastSimOptions()); }, {fragment});
  };
  SimRequest r = test::shortScenario(dir.file("out"));
  r.scenario.clear();
  r.trajectory_file = dir.file("missing.txt");
  expectError(r, "missing.txt: cannot open");
  r.trajectory_file = dir.write("gap.txt", "1.0 0 0 1 0 0 0 1\n1.1 0 0 1 0 0 0 1\n3.0 0 0 1 0 0 0 1\n3.1 0 0 1 0 0 0 1\n");
  r.start_s = 0.0;
  r.duration_s = 2.0;
  expectError(r, "gap of 1.900 s");
  r.trajectory_file = dir.write("short.txt", "1.0 0 0 1 0 0 0 1\n1.2 0 0 1 0 0 0 1\n");
  r.duration_s = std::numeric_limits<double>::quiet_NaN();
  expectError(r, "too short");
  std::ostringstream big;
  for (int i = 0; i <= 100; ++i) big << 1.0 + i * 0.05 << " " << i * 2.0 << " 0 1 0 0 0 1\n";
  r.trajectory_file = dir.write("big.txt", big.str());
  expectError(r, "max_room_size_m");
  r.trajectory_file = dir.write("ok.txt", "1.0 0 0 1 0 0 0 1\n2.0 0 0 1 0 0 0 1\n3.0 0 0 1 0 0 0 1\n");
  r.start_s = 5.0;
  expectError(r, "was requested");
  r = test::shortScenario(dir.file("out"));
  r.scenario = "loop-the-loop";
  expectError(r, "unknown scenario");
  r = test::shortScenario(dir.file("out"));
  r.imu = dir.write("imu.csv", "#t,w,w,w,a,a,a\n5,0,0,0,0,0,9.8\n10,0,0,0,0,0,9.8\n");
  expectError(r, "IMU log covers");
  r = test::shortScenario(dir.file("out"));
  r.drop_rate = 1.5;
  expectError(r, "--drop-rate");
}

// A hand-held shake: 1 cm at 5 Hz on a slow drift, sampled at 200 Hz. A cubic
// B-spline whose control points are the samples at knot spacing Δ is off by
// about Δ²/6·|p''| (its value at a knot is (c₋ + 4c + c₊)/6), here
// Δ²/6·(2π·5 Hz)²·1 cm: 0.16 mm at the default Δ = 10 ms, 4.1 mm at 50 ms,
// where the images would keep only 67 % of a motion the IMU measured in full.
// Knots are never denser than the file's samples (20 Hz: 50 ms).
TEST(Simulator, FollowsA5HzShakeOfTheTrajectoryFile) {
  TempDir dir;
  const auto shake = [](double t) { return Vec3(0.1 * t + 0.01 * std::sin(2 * kPi * 5.0 * t), 0.05 * t, 1.0); };
  const auto write = [&](const std::string& name, double rate_hz) {
    io::Trajectory file;
    for (int i = 0; i <= static_cast<int>(3.0 * rate_hz); ++i) {
      io::TrajectorySample s;
      s.t_ns = 1000000000LL + static_cast<std::int64_t>(std::llround(i * 1e9 / rate_hz));
      s.T_w_b = geometry::SE3(geometry::SO3(), shake(static_cast<double>(s.t_ns) * 1e-9 - 1.0));
      file.push_back(s);
    }
    io::writeTrajectoryTum(dir.file(name), file);
    return dir.file(name);
  };
  SimRequest r;
  r.out_dir = dir.file("out");
  r.trajectory_file = write("shake_200hz.txt", 200.0);
  r.start_s = 1.0;
  r.duration_s = 0.6;
  const SimSummary summary = simulate(r, test::fastSimOptions());
  EXPECT_DOUBLE_EQ(summary.knot_dt_s, test::fastSimOptions().knot_dt_s);
  const double bound = summary.knot_dt_s * summary.knot_dt_s / 6.0 * std::pow(2 * kPi * 5.0, 2) * 0.01;
  double worst = 0.0;
  for (const auto& s : io::readTrajectory(r.out_dir + "/mav0/state_groundtruth_estimate0/data.csv"))
    worst = std::max(worst, (s.T_w_b.translation() - shake(static_cast<double>(s.t_ns) * 1e-9 - 1.0)).norm());
  EXPECT_LT(worst, 1.1 * bound);
  EXPECT_LT(bound, 2e-4);

  r.out_dir = dir.file("out20");
  r.trajectory_file = write("shake_20hz.txt", 20.0);
  EXPECT_DOUBLE_EQ(simulate(r, test::fastSimOptions()).knot_dt_s, 0.05);
}

// At 45.000 s EuRoC MH_04's ground truth jumps 13 cm for one sample and back
// (a tracker glitch). A body's acceleration is bounded by what its
// accelerometer reads: |a| ≤ |f| + g. The rendered motion must keep to that
// bound (+1 m/s² for bias and noise) around the glitch, as it does without
// removePositionSteps only if the glitch is in no knot's reach.
TEST(Simulator, RendersTheMachineHallWithoutItsTrackerGlitch) {
  EDGEVIO_REQUIRE_SHARED_DATA("trajectories/euroc/MH_04_difficult");
  const auto maxAccelExcess = [&](const SimOptions& options) {
    TempDir dir;
    const SimSummary summary = simulate(test::replayRequest(data_path, dir.path(), 44.8, 0.5), options);
    EXPECT_EQ(summary.position_steps_removed > 0, options.trajectory_max_accel_mps2 > 0);
    const auto imu = io::readImuCsv(dir.path() + "/mav0/imu0/data.csv", 1.0, nullptr);
    const io::Trajectory gt = io::readTrajectory(dir.path() + "/mav0/state_groundtruth_estimate0/data.csv");
    EXPECT_EQ(gt.size(), imu.size());
    double max_force = 0.0, max_accel = 0.0;
    for (const auto& s : imu) max_force = std::max(max_force, s.accel.norm());
    for (std::size_t i = 1; i < gt.size(); ++i)
      max_accel = std::max(max_accel, (gt[i].v_w - gt[i - 1].v_w).norm() / (1e-9 * static_cast<double>(gt[i].t_ns - gt[i - 1].t_ns)));
    return max_accel - (max_force + 9.81 + 1.0);
  };
  SimOptions options = test::fastSimOptions();
  EXPECT_LT(maxAccelExcess(options), 0.0);
  options.trajectory_max_accel_mps2 = 0.0;  // the file as is: the test can tell
  EXPECT_GT(maxAccelExcess(options), 0.0);
}

}  // namespace
}  // namespace edgevio::sim
