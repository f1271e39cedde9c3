// The convergence basin of edge alignment (issue #5, cf. the paper's Fig. 4),
// on rendered frames with known motion: success rate
//  (a) against the initial rotation error (one frame apart, the true pose
//      rotated by θ about a random axis, translation from the truth), and
//  (b) against frames skipped (k frames apart, from the identity and from a
//      gyro-like prior: true rotation, zero translation).
// Success: final error below 1 cm and 0.2 deg. Prints markdown tables.
#include <cstdio>
#include <random>

#include <opencv2/core/utility.hpp>

#include "frontend_fixture.h"
#include "edgevio/sim/random.h"
#include "edgevio/tracking/edge_alignment.h"
#include "edgevio/vision/keyframe_depth.h"

using namespace edgevio;

namespace {

struct View {
  std::size_t sample;
  vision::EdgePyramid pyr;
  vision::KeyframeDepth depth;
};

bool success(const geometry::SE3& truth, const geometry::SE3& est) {
  const geometry::SE3 E = truth.inverse() * est;
  return E.translation().norm() < 0.01 && geometry::angle(E.so3()) * kRadToDeg < 0.2;
}

}  // namespace

int main() {
  cv::setNumThreads(1);
  bench::FrontendFixture fx;
  const vision::VisionOptions vo;
  const tracking::AlignmentOptions ao;
  std::vector<std::size_t> starts;
  for (std::size_t i = 400; i + 110 < fx.path.size(); i += 110) starts.push_back(i);
  std::printf("# Convergence basin of edge alignment\n\n%zu keyframes along the figure8 scenario (20 Hz frames), EuRoC rig,\n"
              "walls at ~1-4 m. Success: error < 1 cm and < 0.2 deg. Keyframes with < 2000 reference points are skipped.\n\n",
              starts.size());
  std::vector<View> views;
  for (std::size_t i : starts) {
    cv::Mat l, r;
    fx.frame(i, &l, &r);
    View v{i, vision::buildEdgePyramid(l, fx.rect->rectifiedCamera(), vo), {}};
    v.depth = vision::computeKeyframeDepth(v.pyr, r, fx.rect->baseline(), vo);
    if (v.depth.points[0].size() >= 2000) views.push_back(std::move(v));
  }
  const auto currentPyramid = [&](std::size_t j) {
    cv::Mat l, r;
    fx.frame(j, &l, &r);
    return vision::buildEdgePyramid(l, fx.rect->rectifiedCamera(), vo);
  };

  std::printf("## (a) initial rotation error, one frame apart (%zu keyframes x 4 axes)\n\n| rotation error [deg] | success |\n|---:|---:|\n",
              views.size());
  std::vector<vision::EdgePyramid> next;
  for (const View& v : views) next.push_back(currentPyramid(v.sample + 10));
  sim::Rng rng(5);
  for (double deg : {0.0, 2.0, 4.0, 6.0, 8.0, 10.0, 15.0, 20.0, 30.0}) {
    int ok = 0, n = 0;
    for (std::size_t k = 0; k < views.size(); ++k) {
      const geometry::SE3 truth = fx.relative(views[k].sample, views[k].sample + 10);
      for (int a = 0; a < 4; ++a) {
        const Vec3 axis = Vec3(rng.gaussian(), rng.gaussian(), rng.gaussian()).normalized();
        const geometry::SE3 init(truth.so3() * geometry::SO3::exp(axis * deg * kDegToRad), truth.translation());
        ok += success(truth, tracking::alignEdges(views[k].depth, next[k], init, ao).T_nr);
        ++n;
      }
    }
    std::printf("| %.0f | %d/%d (%.0f %%) |\n", deg, ok, n, 100.0 * ok / n);
  }

  std::printf("\n## (b) frames skipped (k frames apart at 20 Hz)\n\n| k | mean motion | from identity | from gyro-like prior |\n|---:|---:|---:|---:|\n");
  for (int k : {1, 2, 3, 4, 5, 6, 8, 10}) {
    int ok_id = 0, ok_gyro = 0, n = 0;
    double motion = 0.0, rot = 0.0;
    for (const View& v : views) {
      const std::size_t j = v.sample + static_cast<std::size_t>(k) * 10;
      if (j >= fx.path.size()) continue;
      const vision::EdgePyramid cur = currentPyramid(j);
      const geometry::SE3 truth = fx.relative(v.sample, j);
      motion += truth.translation().norm();
      rot += geometry::angle(truth.so3()) * kRadToDeg;
      ok_id += success(truth, tracking::alignEdges(v.depth, cur, geometry::SE3(), ao).T_nr);
      ok_gyro += success(truth, tracking::alignEdges(v.depth, cur, geometry::SE3(truth.so3(), Vec3::Zero()), ao).T_nr);
      ++n;
    }
    std::printf("| %d | %.2f m, %.1f deg | %d/%d | %d/%d |\n", k, motion / n, rot / n, ok_id, n, ok_gyro, n);
  }
  return 0;
}
