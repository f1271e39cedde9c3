// `edgevio simulate` end to end on short sequences: a readable ASL folder,
// byte-identical output for a seed, skips, a replayed real IMU log, the
// world brought back from the folder's simulation.yaml.
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
#include "edgevio/sim/simulation_record.h"
#include "edgevio/geometry/types.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/io/imu_io.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/sim/random.h"
#include "edgevio/sim/renderer.h"
#include "edgevio/sim/sensor_model.h"

namespace edgevio::sim {
namespace {

namespace fs = std::filesystem;
using test::TempDir;

TEST(Simulator, WritesAnAslFolderTheReaderAccepts) {
  TempDir dir;
  SimRequest r = test::shortScenario(dir.path());
  r.drop_rate = 0.3;
  r.blur_ms = 4.0;
  r.exposure_changes = true;
  const SimSummary s = simulate(r, test::fastSimOptions());
  EXPECT_EQ(s.frames, 13u);  // 0.6 s at 20 Hz, both ends included
  EXPECT_GT(s.dropped_cam1, 0u);

  io::EurocDataset d(dir.path(), io::DatasetOptions{});
  EXPECT_EQ(d.stereoPairs().size(), s.frames - s.dropped_cam1);
  EXPECT_EQ(d.unpairedFrames(0), s.dropped_cam1);
  EXPECT_EQ(d.imu().size(), 121u);
  EXPECT_EQ(d.groundTruth().size(), 121u);
  EXPECT_TRUE(d.groundTruth().front().hasVelocityAndBias());
  EXPECT_TRUE(d.warnings().size() == 1u) << "only the unpaired-frames warning is expected";
  const auto pair = d.loadStereo(0);
  ASSERT_TRUE(pair.has_value());
  EXPECT_EQ(pair->left.cols, 752);
  // Calibration written and read back.
  const camera::StereoRig rig = io::eurocDefaultRig();
  EXPECT_NEAR(d.calibration().cam[1].fx, rig.cam[1].fx, 1e-12);
  EXPECT_LT((d.calibration().T_b_c[1].matrix() - rig.T_b_c[1].matrix()).norm(), 1e-9);
  // An image has texture: a fair spread of intensities, not saturated.
  cv::Scalar mean, stddev;
  cv::meanStdDev(pair->left, mean, stddev);
  EXPECT_GT(mean[0], 50.0);
  EXPECT_LT(mean[0], 200.0);
  EXPECT_GT(stddev[0], 20.0);
}

TEST(Simulator, SameSeedGivesByteIdenticalOutput) {
  TempDir a, b, c;
  SimRequest r = test::shortScenario(a.path());
  r.duration_s = 0.5;
  simulate(r, test::fastSimOptions());
  r.out_dir = b.path();
  simulate(r, test::fastSimOptions());
  r.out_dir = c.path();
  r.seed = 4;
  simulate(r, test::fastSimOptions());
  std::size_t files = 0;
  for (const auto& e : fs::recursive_directory_iterator(fs::path(a.path()) / "mav0")) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), a.path());
    EXPECT_EQ(test::readFile(e.path().string()), test::readFile((fs::path(b.path()) / rel).string())) << rel;
    ++files;
  }
  EXPECT_GT(files, 20u);
  const std::string img = "mav0/cam0/data/1600000001500000000.png";
  EXPECT_NE(test::readFile((fs::path(a.path()) / img).string()), test::readFile((fs::path(c.path()) / img).string()))
      << "another seed, another noise";
}

TEST(Simulator, SkipKeepsEveryKPlusOneFrameAndTheImu) {
  TempDir dir;
  SimRequest r = test::shortScenario(dir.path());
  r.skip = 2;
  const SimSummary s = simulate(r, test::fastSimOptions());
  EXPECT_EQ(s.frames, 5u);  // t = 0, 0.15, 0.3, 0.45, 0.6
  EXPECT_EQ(s.imu_samples, 121u);
}

TEST(Simulator, ImuTimeOffsetStampsTheImuLateAndNothingElse) {
  TempDir a, b;
  sim::SimOptions late = test::fastSimOptions();
  late.imu_time_offset_ms = 7.0;
  simulate(test::shortScenario(a.path()), test::fastSimOptions());
  simulate(test::shortScenario(b.path()), late);
  const auto imu_a = io::readImuCsv(a.path() + "/mav0/imu0/data.csv", 1.0, nullptr);
  const auto imu_b = io::readImuCsv(b.path() + "/mav0/imu0/data.csv", 1.0, nullptr);
  ASSERT_EQ(imu_a.size(), imu_b.size());
  for (std::size_t i = 0; i < imu_a.size(); ++i) {
    EXPECT_EQ(imu_b[i].t_ns - imu_a[i].t_ns, 7000000);
    EXPECT_EQ(imu_b[i].gyro, imu_a[i].gyro);
  }
  // Images and ground truth stay on the cameras' (true) clock.
  for (const char* file : {"/mav0/cam0/data.csv", "/mav0/state_groundtruth_estimate0/data.csv"})
    EXPECT_EQ(test::readFile(a.path() + file), test::readFile(b.path() + file)) << file;
}

TEST(Simulator, ReplaysARealImuLogAndKeepsItsBiases) {
  EDGEVIO_REQUIRE_SHARED_DATA("trajectories/euroc/V1_02_medium");
  TempDir dir;
  const SimRequest r = test::replayRequest(data_path, dir.path(), 10.0, 0.5);
  simulate(r, test::fastSimOptions());
  const auto real = io::readImuCsv(r.imu, 1.0, nullptr);
  const auto written = io::readImuCsv(dir.path() + "/mav0/imu0/data.csv", 1.0, nullptr);
  ASSERT_GT(written.size(), 90u);
  const auto it = std::find_if(real.begin(), real.end(), [&](const imu::ImuSample& s) { return s.t_ns == written.front().t_ns; });
  ASSERT_NE(it, real.end());
  for (std::size_t i = 0; i < written.size(); ++i) {
    EXPECT_EQ(written[i].t_ns, (it + static_cast<long>(i))->t_ns);
    EXPECT_EQ(written[i].accel, (it + static_cast<long>(i))->accel);
  }
  const io::Trajectory gt = io::readTrajectory(dir.path() + "/mav0/state_groundtruth_estimate0/data.csv");
  EXPECT_TRUE(gt.front().hasVelocityAndBias());
}

/// Camera 0's image at t rendered from `world` as simulate renders it (no
/// blur, no exposure changes).
cv::Mat renderLeft(const SimulatedWorld& world, const SimOptions& o, std::uint64_t seed, std::int64_t t) {
  cv::Mat radiance;
  render(world.scene, RayTable(world.rig.cam[0]), world.motion.pose(t) * world.rig.T_b_c[0], RenderOptions{}, &radiance);
  const SensorEffects fx{o.exposure_gain, o.vignetting, o.image_noise_sigma};
  return sensorImage(radiance, world.rig.cam[0], fx, hashCombine(seed, static_cast<std::uint64_t>(t) * 2));
}

TEST(Simulator, ItsRecordBringsBackTheWorldItsImagesWereRenderedFrom) {
  TempDir dir;
  const SimRequest r = test::shortScenario(dir.path());
  SimOptions o = test::fastSimOptions();
  o.scene.texture_tile_m = 3.0;  // not the default: the record must carry the options
  simulate(r, o);

  const SimulationRecord record = loadSimulationRecord(dir.path());
  EXPECT_EQ(record.request.scenario, r.scenario);
  EXPECT_EQ(record.request.seed, r.seed);
  EXPECT_EQ(record.request.start_s, r.start_s);
  EXPECT_EQ(record.request.duration_s, r.duration_s);
  EXPECT_EQ(record.options.scene.texture_tile_m, 3.0);
  EXPECT_EQ(record.options.scene.texture_log2_size, 8);

  // A frame rendered again from the world the record brings back is, byte for
  // byte, the folder's image; another seed's world (scene and noise) is not.
  io::EurocDataset d(dir.path(), io::DatasetOptions{});
  const std::size_t i = 7;
  const auto pair = d.loadStereo(i);
  ASSERT_TRUE(pair.has_value());
  const std::int64_t t = d.stereoPairs()[i].t_ns;
  const SimulatedWorld world = simulatedWorld(record.request, record.options);
  EXPECT_EQ(cv::norm(renderLeft(world, record.options, record.request.seed, t), pair->left, cv::NORM_INF), 0.0);
  SimRequest other = record.request;
  other.seed += 1;
  EXPECT_GT(cv::norm(renderLeft(simulatedWorld(other, record.options), record.options, other.seed, t), pair->left,
                     cv::NORM_L1) / static_cast<double>(pair->left.total()), 5.0);

  // A run to the trajectory's end is recorded as duration nan; a bad value names the file and line.
  const fs::path yaml = fs::path(dir.path()) / "simulation.yaml";
  std::string text = test::readFile(yaml.string());
  const std::size_t at = text.find("duration_s: ");
  text.replace(at, text.find('\n', at) - at, "duration_s: nan");
  std::ofstream(yaml) << text;
  EXPECT_TRUE(std::isnan(loadSimulationRecord(dir.path()).request.duration_s));
  const std::size_t seed_at = text.find("seed: ");
  text.replace(seed_at, text.find('\n', seed_at) - seed_at, "seed: three");
  std::ofstream(yaml) << text;
  test::expectInputError([&] { loadSimulationRecord(dir.path()); }, {"simulation.yaml:6", "'seed': expected a number"});
  text.replace(text.find("seed: three"), 11, "seed: 3");
  const std::size_t noise_at = text.find("noise: ");
  text.replace(noise_at, text.find('\n', noise_at) - noise_at, "noise: maybe");
  std::ofstream(yaml) << text;
  test::expectInputError([&] { loadSimulationRecord(dir.path()); }, {"simulation.yaml:8", "'noise': expected true or false"});
  text.replace(text.find("noise: maybe"), 12, "noise: true");
  const std::size_t faults_at = text.find("faults: ");
  text.replace(faults_at, text.find('\n', faults_at) - faults_at, "faults:\n  - \"black:at=1\"\n  - \"quake:at=2\"");
  std::ofstream(yaml) << text;
  test::expectInputError([&] { loadSimulationRecord(dir.path()); }, {"simulation.yaml:16", "'faults':", "quake"});
}

}  // namespace
}  // namespace edgevio::sim
