// What a real rig does wrong, all in one 4 s render (edgevio simulate
// --fault), run in every mode: no run fails or loses a frame silently, the
// blackout is a lost interval that covers it and ends, and the IMU dropout
// restarts the window once.
#include <gtest/gtest.h>

#include <string>

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
  TempDir dir;
  std::string dataset = test::renderFigure8(dir.file("data"), allFaults());
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
  std::size_t rows = 0, lost_rows = 0;
  while (frames.next()) {
    ++rows;
    lost_rows += frames.field(frames.column("status")) == "lost";
  }
  EXPECT_EQ(rows, s.frames);
  // The blackout [0.6, 1.2) s: lost from its first frame, declared at the
  // tenth, tracked again within two frames of its end; nothing else is lost.
  ASSERT_EQ(s.lost_intervals.size(), 1u) << modeName(mode);
  const LostInterval& l = s.lost_intervals[0];
  EXPECT_NEAR(l.start_s, 0.6, 1e-6);
  EXPECT_GE(l.end_s, 1.2);
  EXPECT_LE(l.end_s, 1.3);
  EXPECT_FALSE(l.open);
  // From the tenth failure (1.05 s) to the first frame after the blackout
  // (1.20 s), which fails too: its keyframe is the last black frame.
  EXPECT_EQ(lost_rows, 4u);
  // The IMU dropout: one restart, when the IMU is back.
  EXPECT_EQ(s.estimator_resets, mode.imu ? 1u : 0u);
  test::expectContainsAll(test::readFile(out.file("summary.json")), {"\"lost_intervals\": [", "estimate lost", "tracking again", "\"unaccounted_frames\": 0,"});
}

TEST(FrozenImages, AreALossWhereTheGyroscopeContradictsTheVisualEstimate) {
  // 4 s of the aggressive scenario whose images freeze for 0.5 s from 2 s.
  // Edge-only aligns the repeated images to its keyframe and rotates 2-3 deg
  // per frame less than the gyroscope says (the self check passes on some):
  // lost from the third contradiction's first, until the window of 10
  // frames clears after the images move again. The full system follows the
  // gyroscope through the frozen frames: nothing is lost.
  TempDir dir;
  sim::SimRequest req = test::scenarioRequest(dir.file("data"), "aggressive", 0.0, 4.0, 2);
  req.faults = {sim::parseFault("frozen:at=2,for=0.5")};
  sim::simulate(req, sim::SimOptions{});
  for (const Mode mode : {kEdgeOnly, kFull}) {
    TempDir out;
    const RunSummary s = run(RunRequest(req.out_dir, out.path(), mode), Config{});
    EXPECT_EQ(s.unaccountedFrames(), 0);
    if (mode.imu) {
      EXPECT_TRUE(s.lost_intervals.empty()) << s.lossText();
      continue;
    }
    ASSERT_EQ(s.lost_intervals.size(), 1u) << s.lossText();
    const LostInterval& l = s.lost_intervals[0];
    EXPECT_GE(l.start_s, 2.0);
    EXPECT_LT(l.start_s, 2.5);
    EXPECT_GE(l.end_s, 2.5);
    EXPECT_LE(l.end_s, 3.0);  // at most 10 frames after the images move
    EXPECT_NE(l.reason.find("gyroscope contradicts"), std::string::npos) << l.reason;
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
