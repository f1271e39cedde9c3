// What a real rig does wrong, all in one 4 s render (edgevio simulate
// --fault), run in every mode: no run fails or loses a frame silently, the
// blackout is a lost interval that covers it and ends, and the IMU dropout
// restarts the window once.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "common/sim_fixture.h"
#include "common/test_support.h"
#include "edgevio/common/table_reader.h"
#include "edgevio/io/euroc_dataset.h"
#include "edgevio/pipeline/mode.h"
#include "edgevio/pipeline/run.h"
#include "edgevio/sim/simulator.h"

namespace edgevio::pipeline {
namespace {

using test::TempDir;

const Mode kEdgeOnly{false, false}, kEdgeLoop{false, true}, kEdgeImu{true, false}, kFull{true, true};

/// The run tests' render with every fault, disjoint in time so that each
/// one's effect can be told apart. The blackout lasts 12 frames, beyond
/// tracking.lost_after_failures (10).
std::vector<sim::Fault> allFaults() {
  std::vector<sim::Fault> faults;
  for (const char* spec : {"black:at=0.6,for=0.6", "frozen:at=1.5,for=0.3", "saturated:at=0.3,every=1.7", "occluded:at=2.0,for=0.4",
                           "drop_left:at=2.5", "drop_right:at=2.7", "imu_dropout:at=2.9,for=0.3", "imu_spike:at=1.35",
                           "stamp_duplicate:at=3.5", "stamp_jump:at=3.7,size=60", "stamp_jitter:at=3.8,for=0.2,size=1"})
    faults.push_back(sim::parseFault(spec));
  return faults;
}

struct FaultyRender {
  std::string dataset = test::sharedRender("figure8-every-fault", [](const std::string& out) { test::renderFigure8(out, allFaults()); });
};

const FaultyRender& faultyRender() {
  static const FaultyRender f;
  return f;
}

class Faults : public ::testing::TestWithParam<Mode> {};

TEST_P(Faults, EveryFrameIsAccountedForAndTheBlackoutIsALostInterval) {
  const Mode mode = GetParam();
  TempDir out;
  const RunSummary s = run(RunRequest(faultyRender().dataset, out.path(), mode), Config{});
  EXPECT_FALSE(s.failed) << s.failure;
  // Every left image the render wrote is a row of frames.csv, or skipped
  // with a warning: its stamp repeated or went back (the duplicate, the
  // jump's successors), or its right image was dropped.
  const io::EurocDataset d(faultyRender().dataset, io::DatasetOptions{});
  EXPECT_EQ(d.cameraRows(0), d.frameCount() + d.unreadableImages(0) + d.unpairedFrames(0));
  EXPECT_EQ(d.unpairedFrames(0), 1u);  // drop_right
  EXPECT_EQ(d.unpairedFrames(1), 1u);  // drop_left
  EXPECT_EQ(s.frames, d.frameCount());
  EXPECT_EQ(s.stereo_pairs, d.frameCount());
  EXPECT_EQ(s.frames_to_process, d.frameCount());
  EXPECT_EQ(s.unaccountedFrames(), 0);
  TableReader frames(out.file("frames.csv"), TableReader::Separator::kComma, TableReader::Header::kColumnNames);
  std::size_t rows = 0, lost_rows = 0;  // lost before the timestamp jump
  const double t_first_s = static_cast<double>(d.frameTime(0)) * 1e-9;
  while (frames.next()) {
    ++rows;
    const double t_s = static_cast<double>(std::stoll(frames.field(frames.column("timestamp_ns")))) * 1e-9 - t_first_s;
    lost_rows += frames.field(frames.column("status")) == "lost" && t_s < 3.7;
  }
  EXPECT_EQ(rows, s.frames);
  for (const LostInterval& l : s.lost_intervals)
    std::printf("%s: lost %.2f-%.2f s: %s\n", modeName(mode).c_str(), l.start_s, l.end_s, l.reason.c_str());
  // The blackout [0.6, 1.2) s, tracked again within two frames of its end.
  // Its black frames repeat each other to the last pixel: the visual modes
  // are lost from the second; the IMU modes, which carry the pose through,
  // from the first, declared at the tenth failure. The visual modes lose
  // the frozen images [1.5, 1.8) s too, and track again within two frames
  // of their end (0.35 s of the figure8's motion without a pose between
  // the last image before and the first after). Nothing else is lost before the
  // timestamp jump (3.7 s): at it the poses are stamped 60 ms late, and a
  // visual mode may find them off the accelerometer's prediction (about
  // 0.1 m at the figure8's speed) for a frame or two.
  std::vector<LostInterval> before_jump;
  for (const LostInterval& l : s.lost_intervals) {
    if (l.start_s < 3.7) {
      before_jump.push_back(l);
    } else {
      EXPECT_FALSE(mode.imu) << modeName(mode);
      EXPECT_LE(l.end_s - l.start_s, 0.15) << modeName(mode);
      EXPECT_NE(l.reason.find("accelerometer"), std::string::npos) << l.reason;
    }
  }
  ASSERT_EQ(before_jump.size(), mode.imu ? 1u : 2u) << modeName(mode);
  const LostInterval& l = before_jump[0];
  EXPECT_NEAR(l.start_s, mode.imu ? 0.6 : 0.65, 1e-6);
  EXPECT_GE(l.end_s, 1.2);
  EXPECT_LE(l.end_s, 1.3);
  EXPECT_FALSE(l.open);
  if (!mode.imu) {
    EXPECT_NEAR(before_jump[1].start_s, 1.5, 1e-6);  // the first repeat
    EXPECT_GE(before_jump[1].end_s, 1.85 - 1e-6);    // the first new image
    EXPECT_LE(before_jump[1].end_s, 1.90 + 1e-6);    // or the one after it
  }
  // IMU modes: from the tenth failure (1.05 s) to the first frame after the
  // blackout (1.20 s), which fails too: its keyframe is the last black frame.
  // Visual modes: 0.65-1.20 s and 1.50 s to the first frame tracked again.
  if (mode.imu) {
    EXPECT_EQ(lost_rows, 4u);
  } else {  // before_jump has two intervals (asserted above)
    EXPECT_EQ(lost_rows, 12u + static_cast<std::size_t>(std::lround((before_jump[1].end_s - 1.5) / 0.05)));
  }
  // The IMU dropout: one restart, when the IMU is back.
  EXPECT_EQ(s.estimator_resets, mode.imu ? 1u : 0u);
  test::expectContainsAll(test::readFile(out.file("summary.json")), {"\"lost_intervals\": [", "estimate lost", "tracking again", "\"unaccounted_frames\": 0,"});
}

TEST(FrozenImages, AreALossInTheVisualModesAndTheGyroscopeSeesThem) {
  // 4 s of the aggressive scenario whose images freeze for 0.5 s from 2 s:
  // lost from the first repeated image to the first new one (edge-only at
  // once; the full system at the tenth, as ten failures). Edge-only aligns
  // some repeated images to its keyframe (self check passed) at a rotation
  // 2-3 deg per frame off the gyroscope's; the full system follows the
  // gyroscope.
  TempDir dir;
  sim::SimRequest req = test::scenarioRequest(dir.file("data"), "aggressive", 0.0, 4.0, 2);
  req.faults = {sim::parseFault("frozen:at=2,for=0.5")};
  sim::simulate(req, sim::SimOptions{});
  for (const Mode mode : {kEdgeOnly, kFull}) {
    TempDir out;
    const RunSummary s = run(RunRequest(req.out_dir, out.path(), mode), Config{});
    EXPECT_EQ(s.unaccountedFrames(), 0);
    TableReader frames(out.file("frames.csv"), TableReader::Separator::kComma, TableReader::Header::kColumnNames);
    int repeated = 0, contradicted = 0;
    while (frames.next()) {
      repeated += frames.field(frames.column("frozen_image")) == "1";
      contradicted += frames.numberOrNan(frames.column("gyro_disagreement_deg")) > 2.0;
    }
    EXPECT_EQ(repeated, 10);  // 2.00-2.45 s
    if (mode.imu)
      EXPECT_EQ(contradicted, 0);
    else
      EXPECT_GE(contradicted, 2);
    // Edge-only may lose a few frames after it too: re-acquiring from the
    // stalled pose, its steps there are off the accelerometer's prediction
    // (0.12-0.16 m; its error grows 0.66 -> 0.75 m at 2.65 s).
    ASSERT_GE(s.lost_intervals.size(), 1u) << s.lossText();
    EXPECT_NEAR(s.lost_intervals[0].start_s, 2.0, 1e-6);
    EXPECT_NEAR(s.lost_intervals[0].end_s, 2.5, 1e-6);
    if (mode.imu) {
      EXPECT_EQ(s.lost_intervals.size(), 1u) << s.lossText();
    }
    for (std::size_t i = 1; i < s.lost_intervals.size(); ++i) {
      EXPECT_GE(s.lost_intervals[i].start_s, 2.5) << s.lossText();
      EXPECT_LE(s.lost_intervals[i].end_s, 2.8) << s.lossText();
      EXPECT_NE(s.lost_intervals[i].reason.find("accelerometer"), std::string::npos) << s.lossText();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(AllModes, Faults, ::testing::Values(kEdgeOnly, kEdgeLoop, kEdgeImu, kFull),
                         [](const ::testing::TestParamInfo<Mode>& p) {
                           std::string n = modeName(p.param);
                           for (char& c : n)
                             if (c == '+' || c == '-') c = '_';
                           return n;
                         });

}  // namespace
}  // namespace edgevio::pipeline
