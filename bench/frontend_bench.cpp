// Front-end time per component at 376x240 on one core (issue #5; METHOD.md §9
// Table 1: Canny 2 ms, distance transform 2 ms, block matching 8 ms, edge
// alignment 11 ms on a 1.3 GHz dual core at 320x240).
#include <benchmark/benchmark.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/core/utility.hpp>
#include <opencv2/imgproc.hpp>

#include "frontend_fixture.h"
#include "edgevio/tracking/edge_alignment.h"
#include "edgevio/vision/keyframe_depth.h"

namespace {

using namespace edgevio;

struct Data {
  bench::FrontendFixture fx;
  cv::Mat ref_left, ref_right, cur_left, cur_right;
  vision::EdgePyramid ref_pyr, cur_pyr;
  vision::KeyframeDepth depth;
  geometry::SE3 prior;  // the true pose with the translation unknown (as from a gyro prior)
  Data() {
    cv::setNumThreads(1);  // one core, as the issue asks
    fx.frame(1500, &ref_left, &ref_right);
    fx.frame(1510, &cur_left, &cur_right);
    const vision::VisionOptions vo;
    ref_pyr = vision::buildEdgePyramid(ref_left, fx.rect->rectifiedCamera(), vo);
    cur_pyr = vision::buildEdgePyramid(cur_left, fx.rect->rectifiedCamera(), vo);
    depth = vision::computeKeyframeDepth(ref_pyr, ref_right, fx.rect->baseline(), vo);
    prior = geometry::SE3(fx.relative(1500, 1510).so3(), Vec3::Zero());
  }
};

const Data& data() {
  static const Data d;
  return d;
}

void BM_CannyAllLevels(benchmark::State& state) {
  const Data& d = data();
  const vision::VisionOptions vo;
  cv::Mat edges;
  for (auto _ : state)
    for (const auto& level : d.cur_pyr.levels) {
      const auto [lo, hi] = vision::cannyThresholds(level.image, vo);
      cv::Canny(level.image, edges, lo, hi, 3, true);
    }
  state.SetLabel("adaptive thresholds, 4 levels from 376x240");
}
BENCHMARK(BM_CannyAllLevels)->Unit(benchmark::kMillisecond);

void BM_DistanceTransformAllLevels(benchmark::State& state) {
  const Data& d = data();
  for (auto _ : state)
    for (const auto& level : d.cur_pyr.levels) {
      vision::DistanceTransform dt(level.edges);
      benchmark::DoNotOptimize(dt);
    }
  state.SetLabel("exact EDT + gradient, 4 levels (the paper's component)");
}
BENCHMARK(BM_DistanceTransformAllLevels)->Unit(benchmark::kMillisecond);

// OpenCV's exact transform (no nearest pixel) on the same maps, for reference.
void BM_OpenCvDistanceTransformAllLevels(benchmark::State& state) {
  const Data& d = data();
  cv::Mat background, dist;
  for (auto _ : state)
    for (const auto& level : d.cur_pyr.levels) {
      cv::compare(level.edges, 0, background, cv::CMP_EQ);
      cv::distanceTransform(background, dist, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
      benchmark::DoNotOptimize(dist);
    }
  state.SetLabel("cv::distanceTransform DIST_MASK_PRECISE, for reference");
}
BENCHMARK(BM_OpenCvDistanceTransformAllLevels)->Unit(benchmark::kMillisecond);

void BM_EdgeLinesLevel0(benchmark::State& state) {
  const Data& d = data();
  const auto& level = d.cur_pyr.levels[0];
  double lines = 0.0;
  for (auto _ : state) {
    vision::DistanceTransform dt(level.edges, level.image);
    lines = dt.linesMs();
  }
  state.counters["lines_ms"] = lines;
  state.counters["edges"] = level.edge_count;
  state.SetLabel("level-0 EDT + sub-pixel edge lines and nearest-edge map (edgevio's addition)");
}
BENCHMARK(BM_EdgeLinesLevel0)->Unit(benchmark::kMillisecond);

// The pyramid thread's whole work per frame: halving, Canny, distance
// transforms and the level-0 edge lines, from the rectified 752x480 image.
void BM_EdgePyramid(benchmark::State& state) {
  const Data& d = data();
  const vision::VisionOptions vo;
  for (auto _ : state) benchmark::DoNotOptimize(vision::buildEdgePyramid(d.cur_left, d.fx.rect->rectifiedCamera(), vo));
  state.SetLabel("buildEdgePyramid: 4 levels from 752x480 (the pyramid thread per frame)");
}
BENCHMARK(BM_EdgePyramid)->Unit(benchmark::kMillisecond);

void BM_StereoBlockMatching(benchmark::State& state) {
  const Data& d = data();
  const vision::VisionOptions vo;
  for (auto _ : state) benchmark::DoNotOptimize(vision::computeKeyframeDepth(d.ref_pyr, d.ref_right, d.fx.rect->baseline(), vo));
  state.SetLabel("StereoBM 64 disparities, block 13, 376x240, + depth pooling (per keyframe)");
}
BENCHMARK(BM_StereoBlockMatching)->Unit(benchmark::kMillisecond);

void BM_EdgeAlignment(benchmark::State& state) {
  const Data& d = data();
  const tracking::AlignmentOptions ao;
  int iterations = 0;
  for (auto _ : state) {
    const tracking::AlignmentResult r = tracking::alignEdges(d.depth, d.cur_pyr, d.prior, ao);
    iterations = r.iterations;
  }
  state.counters["points"] = static_cast<double>(d.depth.points[0].size());
  state.counters["iterations"] = iterations;
  state.SetLabel("one frame apart, gyro-like prior");
}
BENCHMARK(BM_EdgeAlignment)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
