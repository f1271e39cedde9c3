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
  for (int i = 0; i < 3; ++i) s.count(someRecord(1000000000 + i), 1000000000, 2);
  EXPECT_EQ(s.frames, 3u);
  EXPECT_EQ(s.keyframes, 3u);
  EXPECT_EQ(s.external_check_rejections, 3u);
  EXPECT_EQ(s.loop_closures, 6u);
  EXPECT_FALSE(s.failed);
  s.count(failed, 1000000000, 2);
  EXPECT_FALSE(s.failed);
  s.count(someRecord(2050000000), 1000000000, 2);  // a passing frame in between: not two in a row
  s.count(failed, 1000000000, 2);
  EXPECT_FALSE(s.failed);
  s.count(failed, 1000000000, 2);
  EXPECT_TRUE(s.failed);
  EXPECT_NE(s.failure.find("2 consecutive self-check failures"), std::string::npos) << s.failure;
  EXPECT_EQ(s.self_check_failures, 3u);
}

TEST(RunSummary, LatencyPercentilesAreNearestRank) {
  RunSummary s;
  EXPECT_EQ(s.latencyPercentile(50), 0.0);
  // Latencies 100, 99, ..., 1 ms: the p-th percentile of 1..100 by nearest rank is p.
  for (int i = 100; i >= 1; --i) {
    FrameRecord r = someRecord(1000000000 + i);
    r.latency_ms = i;
    s.count(r, 1000000000, 10);
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
