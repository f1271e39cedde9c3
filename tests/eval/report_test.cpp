// Reports, plots and batch evaluation of run folders.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "common/test_support.h"
#include "edgevio/cli/commands.h"
#include "edgevio/eval/batch.h"
#include "edgevio/eval/report.h"
#include "edgevio/eval/svg_plot.h"

namespace edgevio::eval {
namespace {

using geometry::SE3;
using geometry::SO3;
using test::TempDir;

io::Trajectory circle(double offset_m) {
  io::Trajectory t;
  for (int i = 0; i < 400; ++i) {
    io::TrajectorySample s;
    s.t_ns = 5000000000LL + i * 50000000LL;
    const double a = i * 0.02;
    s.T_w_b = SE3(SO3::exp(Vec3(0, 0, a)), Vec3(2 * std::cos(a) + offset_m * std::sin(7 * a), 2 * std::sin(a), 1));
    t.push_back(s);
  }
  return t;
}


TEST(Report, JsonHasTheDocumentedKeys) {
  const EvalResult r = evaluate(circle(0), circle(0.05), EvalOptions{});
  std::ostringstream o;
  writeJson(o, r);
  test::expectContainsAll(o.str(), {"\"matched\"", "\"align\"", "\"ate_rmse_m\"", "\"ate_mean_m\"", "\"ate_median_m\"",
                                    "\"ate_max_m\"", "\"rpe\"", "\"delta_m\"", "\"trans_rmse_m\"", "\"rot_rmse_deg\"",
                                    "\"are_rot_deg_per_m\"", "\"are_trans_m_per_m\"", "\"length_m\"", "\"duration_s\""});
  std::ostringstream t;
  writeTable(t, r);
  EXPECT_NE(t.str().find("ATE RMSE"), std::string::npos);
}

TEST(Report, SvgPlotIsReadable) {
  const EvalResult r = evaluate(circle(0), circle(0.05), EvalOptions{});
  const std::string svg = svgPlot(r, "circle <test>");
  EXPECT_EQ(svg.rfind("<svg", 0), 0u);
  EXPECT_NE(svg.find("</svg>"), std::string::npos);
  test::expectContainsAll(svg, {"x [m]", "y [m]", "ATE [m]", "ground truth", "estimate (aligned)", "circle &lt;test&gt;"});
  // Two data polylines in the top view plus the ATE curve.
  std::size_t count = 0;
  for (std::size_t p = svg.find("<polyline"); p != std::string::npos; p = svg.find("<polyline", p + 1)) ++count;
  EXPECT_EQ(count, 3u);
  EXPECT_EQ(svg.find("nan"), std::string::npos);
}

TEST(Report, BatchMarksFailuresAndEvaluatesTheRest) {
  TempDir dir;
  io::writeTrajectoryEuroc(dir.file("gt.csv"), circle(0));
  // ok run: ground truth named in summary.json
  for (const char* sub : {"seqA/edge+imu", "seqB", "seqC"}) std::filesystem::create_directories(dir.file(sub));
  io::writeTrajectoryTum(dir.file("seqA/edge+imu/trajectory_tum.txt"), circle(0.02));
  dir.write("seqA/edge+imu/summary.json",
            "{\"mode\": \"edge+imu\", \"sequence\": \"seqA\", \"failed\": false, \"groundtruth\": \"../../gt.csv\", "
            "\"realtime_factor\": 7.5, \"latency_ms\": {\"p50\": 12.5, \"p99\": 40.25, \"max\": 51}, \"lost_intervals\": "
            "[{\"start_s\": 2, \"end_s\": 2.5, \"reason\": \"a\"}, {\"start_s\": 10, \"end_s\": 11, \"reason\": \"b\"}], "
            "\"frames\": 397, \"frames_to_process\": 400, \"unaccounted_frames\": 2}");
  // failed run, of the odd frames
  dir.write("seqA/edge-only/summary.json",
            "{\"mode\": \"edge-only\", \"sequence\": \"seqA\", \"failed\": true, \"skip\": 1, \"skip_offset\": 1}");
  // run without ground truth
  io::writeTrajectoryTum(dir.file("seqB/trajectory_tum.txt"), circle(0));
  // run whose estimate has no overlap with its ground truth
  io::Trajectory late = circle(0);
  for (auto& s : late) s.t_ns += 1000000000000LL;
  io::writeTrajectoryTum(dir.file("seqC/trajectory_tum.txt"), late);
  io::writeTrajectoryEuroc(dir.file("seqC/groundtruth.csv"), circle(0));

  const auto runs = evaluateRunFolders(dir.path(), EvalOptions{});
  ASSERT_EQ(runs.size(), 4u);
  std::size_t ok = 0;
  for (const auto& r : runs) ok += r.ok;
  EXPECT_EQ(ok, 1u);
  std::ostringstream out, err;
  ASSERT_EQ(cli::evalResults(dir.path(), EvalOptions{}, out, err), cli::kExitOk) << err.str();
  const std::string md = test::readFile(dir.file("report.md")), csv = test::readFile(dir.file("report.csv"));
  EXPECT_NE(md.find("4 runs, 3 failed"), std::string::npos) << md;
  // Time to recover: the longest loss; frames lost without a word come first.
  EXPECT_NE(md.find("| seqA | edge+imu | **2 frames unaccounted**; lost 1.5 s (longest 1.0 s); 3 segments, ATE <= "),
            std::string::npos)
      << md;
  EXPECT_NE(md.find(" | 397/400 | 400 | "), std::string::npos) << md;
  EXPECT_NE(md.find("| seqA | edge-only, skip 1 from frame 1 | **FAILED**"), std::string::npos) << md;
  EXPECT_NE(md.find("no ground truth"), std::string::npos) << md;
  EXPECT_NE(md.find("no timestamp overlap"), std::string::npos) << md;
  EXPECT_NE(csv.find("seqA,edge+imu,seqA/edge+imu,ok,,400,se3,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",7.50,0,0,,12.50,40.25,2,1.500,3,"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",1.000,397,400,2\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find(",0,0,,,,0,0.000,0,,0.000,,,\n"), std::string::npos) << csv;  // a summary without them: empty fields, nothing lost
  EXPECT_NE(csv.find(",1,1,,,,0,0.000,"), std::string::npos) << csv;  // skip and skip_offset of the failed run
}

TEST(Report, SegmentsBetweenLossesAreEvaluatedAlone) {
  // The estimate jumps 1 m during its one loss (10-11 s after its first
  // pose): the whole run's ATE carries the jump, each segment is exact.
  io::Trajectory est = circle(0);
  for (auto& s : est)
    if (s.t_ns - est.front().t_ns > 10500000000LL) s.T_w_b = SE3(s.T_w_b.so3(), s.T_w_b.translation() + Vec3(1, 0, 0));
  const std::vector<io::Trajectory> segments = segmentsBetweenLosses(est, {{10.0, 11.0}});
  ASSERT_EQ(segments.size(), 2u);
  EXPECT_EQ(segments[0].size(), 200u);  // 0-9.95 s
  EXPECT_EQ(segments[1].size(), 179u);  // 11.05-19.95 s
  EXPECT_TRUE(segmentsBetweenLosses(est, {{0.0, 19.0}}).empty()) << "a piece under kMinSegmentPoses is left out";
  TempDir dir;
  std::filesystem::create_directories(dir.file("run"));
  io::writeTrajectoryEuroc(dir.file("run/groundtruth.csv"), circle(0));
  io::writeTrajectoryTum(dir.file("run/trajectory_tum.txt"), est);
  dir.write("run/summary.json", "{\"lost_intervals\": [{\"start_s\": 10, \"end_s\": 11, \"reason\": \"x\"}]}");
  const auto runs = evaluateRunFolders(dir.path(), EvalOptions{});
  ASSERT_EQ(runs.size(), 1u);
  ASSERT_TRUE(runs[0].ok) << runs[0].failure;
  EXPECT_GT(runs[0].result.ate_rmse_m, 0.3);
  ASSERT_EQ(runs[0].segment_ate_m.size(), 2u);
  for (double ate : runs[0].segment_ate_m) EXPECT_LT(ate, 1e-6);
}

TEST(EvalCommand, SegmentsAndErrors) {
  TempDir dir;
  io::writeTrajectoryTum(dir.file("gt.txt"), circle(0));
  io::writeTrajectoryTum(dir.file("est.txt"), circle(0.03));
  cli::EvalArgs a;
  a.gt = dir.file("gt.txt");
  a.est = dir.file("est.txt");
  a.format = "json";
  a.segments = "2m,4m";
  a.plot = dir.file("plot.svg");
  std::ostringstream out, err;
  ASSERT_EQ(cli::eval(a, out, err), cli::kExitOk) << err.str();
  EXPECT_NE(out.str().find("\"are_lengths_m\": [\n    2,\n    4\n  ]"), std::string::npos) << out.str();
  EXPECT_NE(test::readFile(a.plot).find("</svg>"), std::string::npos);

  for (const std::string bad : {"10", "5km", "10%,2m", "%"}) {
    a.segments = bad;
    std::ostringstream o2, e2;
    EXPECT_EQ(cli::eval(a, o2, e2), cli::kExitError) << bad;
    EXPECT_NE(e2.str().find("--segments"), std::string::npos) << e2.str();
  }
  a.segments = "";
  a.est = dir.write("garbage.txt", "hello world\n");
  std::ostringstream o3, e3;
  EXPECT_EQ(cli::eval(a, o3, e3), cli::kExitError);
  EXPECT_NE(e3.str().find("garbage.txt:1"), std::string::npos) << e3.str();
}

}  // namespace
}  // namespace edgevio::eval
