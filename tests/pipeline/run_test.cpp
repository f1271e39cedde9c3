// The run's inputs and outputs without running the system on images: bad
// requests are errors, the frame record's table writes and reads back, the
// summary counts the records.
#include "edgevio/pipeline/run.h"

#include <gtest/gtest.h>

#include <sstream>

#include "common/mini_dataset.h"
#include "common/test_support.h"
#include "edgevio/common/error.h"
#include "edgevio/common/table_reader.h"
#include "edgevio/pipeline/component_times.h"
#include "edgevio/pipeline/run_writer.h"

namespace edgevio::pipeline {
namespace {

using test::TempDir;

TEST(Run, BadInputIsAnError) {
  TempDir out;
  const std::string mini = test::writeMiniDataset(out);
  const Mode edge_only{false, false};
  EXPECT_THROW(run({out.file("missing"), out.file("o"), edge_only}, Config{}), InputError);
  EXPECT_THROW(run({mini, out.file("o"), edge_only, -1}, Config{}), InputError);
  // Offsets outside 0..skip, and one past the mini dataset's 5 frames.
  for (const auto& [skip, offset] : {std::pair{0, 1}, std::pair{1, 2}, std::pair{1, -1}, std::pair{5, 5}}) {
    RunRequest r(mini, out.file("o"), edge_only, skip);
    r.skip_offset = offset;
    EXPECT_THROW(run(r, Config{}), InputError) << "skip " << skip << ", offset " << offset;
  }
  Config bad;
  bad.alignment.max_iterations_per_level = 0;
  EXPECT_THROW(run({mini, out.file("o"), edge_only}, bad), InputError);
}

TEST(Mode, NamesAreThePapersAndRoundTrip) {
  EXPECT_EQ(modeName({false, false}), "edge-only");
  EXPECT_EQ(modeName({false, true}), "edge+loop");
  EXPECT_EQ(modeName({true, false}), "edge+imu");
  EXPECT_EQ(modeName({true, true}), "edge+imu+loop");
  for (const bool imu : {false, true})
    for (const bool loop : {false, true}) EXPECT_EQ(*parseMode(modeName({imu, loop})), (Mode{imu, loop}));
  EXPECT_FALSE(parseMode("imu-only"));
}

FrameRecord someRecord(std::int64_t t_ns) {
  FrameRecord r;
  r.t_ns = t_ns;
  r.aligned = true;
  r.alignment.self_check_passed = true;
  r.alignment.ms = 2.5;
  r.reference_t_ns = t_ns - 50000000;
  r.keyframe = tracking::KeyframeReason::kPointsLeavingView;
  r.keyframes_made = 1;
  r.bm_ms = 4.0;
  r.canny_ms = 1.0;
  r.external_check = ExternalCheck::kRejected;
  r.estimator.marginalized = estimator::Marginalization::kFront;
  r.estimator.solve_ms = 1.5;
  r.loop_links = 2;
  return r;
}

TEST(FrameRecord, ARowHasOneCellPerColumnAndReadsBackByName) {
  TempDir dir;
  {
    RunWriter w(dir.path(), Config{}, true);
    w.write(someRecord(1000000000));
    FrameRecord plain = someRecord(1050000000);
    plain.keyframe = tracking::KeyframeReason::kNone;
    plain.bm_ms = 0.0;
    w.write(plain);
  }
  TableReader in(dir.file("frames.csv"), TableReader::Separator::kComma, TableReader::Header::kColumnNames);
  ASSERT_TRUE(in.next());
  EXPECT_EQ(in.size(), frameColumns().size());
  EXPECT_EQ(in.integer(in.column("timestamp_ns")), 1000000000);
  EXPECT_EQ(in.field(in.column("keyframe")), "1");
  EXPECT_EQ(in.field(in.column("keyframe_reason")), "points leaving the view");
  EXPECT_EQ(in.field(in.column("external_check")), "rejected");
  EXPECT_EQ(in.field(in.column("marginalized")), "front");
  EXPECT_EQ(in.number(in.column("align_ms")), 2.5);
  ASSERT_TRUE(in.next());
  EXPECT_EQ(in.field(in.column("keyframe_reason")), "-");
  EXPECT_FALSE(in.next());
  // Per-keyframe components average over the rows where they ran.
  for (const ComponentTime& c : readComponentTimes(dir.file("frames.csv"))) {
    if (c.component == "block matching") {
      EXPECT_EQ(c.count, 1u);
    } else if (c.component == "Canny (pyramid)") {
      EXPECT_EQ(c.count, 2u);
    } else if (c.component == "marginalisation") {
      EXPECT_EQ(c.count, 0u);
    }
  }
}

TEST(RunSummary, CountsTheRecords) {
  RunSummary s;
  FrameRecord failed = someRecord(2000000000);
  failed.alignment.self_check_passed = false;
  for (int i = 0; i < 3; ++i) s.count(someRecord(1000000000 + i), 1000000000);
  s.count(failed, 1000000000);
  EXPECT_EQ(s.frames, 4u);
  EXPECT_EQ(s.keyframes, 4u);
  EXPECT_EQ(s.external_check_rejections, 4u);
  EXPECT_EQ(s.loop_closures, 8u);
  EXPECT_EQ(s.self_check_failures, 1u);
  s.finish();
  EXPECT_FALSE(s.failed);
  // 4 rows, 2 frames dropped in real time, 1 that did not decode: of 8 to
  // process, 1 is lost without a word; of 6, one row has no frame.
  s.dropped_frames = 2;
  s.unreadable_frames = 1;
  s.frames_to_process = 8;
  EXPECT_EQ(s.unaccountedFrames(), 1);
  s.frames_to_process = 6;
  EXPECT_EQ(s.unaccountedFrames(), -1);
}

TEST(RunSummary, LostIntervalsFollowTheFramesStatus) {
  // Frames every 0.1 s from t0 = 1 s; lost from 0.3 s (declared at 0.5 s,
  // its first symptom at 0.3 s) until 0.7 s; lost again from 0.9 s to the end.
  const std::int64_t t0 = 1000000000;
  RunSummary s;
  for (int k = 0; k <= 10; ++k) {
    FrameRecord r = someRecord(t0 + k * 100000000LL);
    const bool lost = (k >= 5 && k < 7) || k >= 9;
    r.status = lost ? TrackingStatus::kLost : TrackingStatus::kOk;
    if (k == 5) r.lost_since_ns = t0 + 300000000, r.lost_reason = "3 consecutive self-check failures";
    if (k == 9) r.lost_since_ns = t0 + 900000000, r.lost_reason = "non-finite pose";
    s.count(r, t0);
  }
  ASSERT_EQ(s.lost_intervals.size(), 2u);
  EXPECT_NEAR(s.lost_intervals[0].start_s, 0.3, 1e-12);
  EXPECT_NEAR(s.lost_intervals[0].end_s, 0.7, 1e-12);
  EXPECT_EQ(s.lost_intervals[0].reason, "3 consecutive self-check failures");
  EXPECT_NEAR(s.lost_intervals[1].start_s, 0.9, 1e-12);
  EXPECT_NEAR(s.lost_intervals[1].end_s, 1.0, 1e-12);
  s.finish();
  EXPECT_FALSE(s.failed) << "a loss is an interval, not the run's verdict";
  std::ostringstream json;
  writeSummaryJson(json, s);
  test::expectContainsAll(json.str(), {"\"lost_intervals\": [", "\"reason\": \"non-finite pose\""});
}

TEST(RunSummary, FailsOnlyWithoutAnEstimate) {
  RunSummary none;
  none.finish();
  EXPECT_TRUE(none.failed);
  RunSummary all_lost;
  FrameRecord r = someRecord(1000000000);
  r.status = TrackingStatus::kLost;
  r.lost_since_ns = r.t_ns;
  all_lost.count(r, r.t_ns);
  all_lost.finish();
  EXPECT_TRUE(all_lost.failed);
  EXPECT_EQ(all_lost.failure, "no frame was tracked");
}

TEST(RunSummary, LatencyPercentilesAreNearestRank) {
  RunSummary s;
  EXPECT_EQ(s.latencyPercentile(50), 0.0);
  // Latencies 100, 99, ..., 1 ms: the p-th percentile of 1..100 by nearest rank is p.
  for (int i = 100; i >= 1; --i) {
    FrameRecord r = someRecord(1000000000 + i);
    r.latency_ms = i;
    s.count(r, 1000000000);
  }
  EXPECT_EQ(s.latencyPercentile(50), 50.0);
  EXPECT_EQ(s.latencyPercentile(99), 99.0);
  EXPECT_EQ(s.latencyPercentile(99.5), 100.0);
  EXPECT_EQ(s.latencyPercentile(100), 100.0);
  EXPECT_EQ(s.latencyPercentile(0.5), 1.0);
}

TEST(Outputs, TheReferenceInDocsIsTheGeneratedOne) {
  std::ostringstream generated;
  writeOutputsReference(generated);
  EXPECT_EQ(test::readFile(test::sourceDir() + "/docs/outputs.md"), generated.str())
      << "docs/outputs.md is out of date: edgevio --print-outputs-reference > docs/outputs.md";
}

}  // namespace
}  // namespace edgevio::pipeline
