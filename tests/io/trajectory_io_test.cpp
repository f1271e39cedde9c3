#include "edgevio/io/trajectory_io.h"

#include <gtest/gtest.h>

#include "common/test_support.h"
#include "edgevio/common/error.h"

namespace edgevio::io {
namespace {

using geometry::SE3;
using geometry::SO3;
using test::TempDir;

Trajectory sampleTrajectory() {
  Trajectory t;
  for (int i = 0; i < 10; ++i) {
    TrajectorySample s;
    s.t_ns = 1403715273262142976LL + i * 50000000LL + (i % 3);  // odd nanoseconds survive round trips
    s.T_w_b = SE3(SO3::exp(Vec3(0.1 * i, -0.05 * i, 0.3)), Vec3(i * 0.5, -1.0 + i, 2.0));
    t.push_back(s);
  }
  return t;
}

void expectSameTrajectory(const Trajectory& a, const Trajectory& b, double tol) {
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].t_ns, b[i].t_ns);
    EXPECT_LT((a[i].T_w_b.translation() - b[i].T_w_b.translation()).norm(), tol);
    EXPECT_LT((a[i].T_w_b.so3().inverse() * b[i].T_w_b.so3()).log().norm(), tol);
  }
}

TEST(TrajectoryIo, TumRoundTripIsNanosecondExact) {
  TempDir dir;
  const Trajectory t = sampleTrajectory();
  writeTrajectoryTum(dir.file("t.txt"), t);
  TrajectoryFormat f;
  const Trajectory r = readTrajectory(dir.file("t.txt"), &f);
  EXPECT_EQ(f, TrajectoryFormat::kTum);
  expectSameTrajectory(t, r, 1e-8);  // 9 printed decimals
}

TEST(TrajectoryIo, EurocRoundTripWithVelocityAndBias) {
  TempDir dir;
  Trajectory t = sampleTrajectory();
  for (auto& s : t) {
    s.v_w = Vec3(1, 2, 3);
    s.b_g = Vec3(1e-3, -2e-3, 3e-4);
    s.b_a = Vec3(0.1, 0.2, -0.3);
  }
  writeTrajectoryEuroc(dir.file("t.csv"), t);
  TrajectoryFormat f;
  const Trajectory r = readTrajectory(dir.file("t.csv"), &f);
  EXPECT_EQ(f, TrajectoryFormat::kEuroc);
  expectSameTrajectory(t, r, 1e-8);
  ASSERT_TRUE(r[3].hasVelocityAndBias());
  EXPECT_LT((r[3].b_g - t[3].b_g).norm(), 1e-12);
}

TEST(TrajectoryIo, StreamedEurocMarksUnknownVelocityAndBias) {
  // A run writes sample by sample; a frame without an estimator state (before
  // the IMU starts, say) gets "nan" there, read back as unknown.
  TempDir dir;
  const Trajectory t = sampleTrajectory();
  {
    TrajectoryWriter w(dir.file("t.csv"), TrajectoryFormat::kEuroc, true);
    for (std::size_t i = 0; i < t.size(); ++i) {
      TrajectorySample s = t[i];
      if (i >= 2) {
        s.v_w = Vec3(1, 2, 3);
        s.b_g = Vec3(1e-3, -2e-3, 3e-4);
        s.b_a = Vec3(0.1, 0.2, -0.3);
      }
      w.write(s);
    }
    EXPECT_EQ(w.count(), t.size());
  }
  const Trajectory r = readTrajectory(dir.file("t.csv"));
  expectSameTrajectory(t, r, 1e-8);
  EXPECT_FALSE(r[1].hasVelocityAndBias());
  ASSERT_TRUE(r[2].hasVelocityAndBias());
  EXPECT_LT((r[2].b_a - Vec3(0.1, 0.2, -0.3)).norm(), 1e-12);
}

TEST(TrajectoryIo, ColumnOrdersOfBothFormats) {
  TempDir dir;
  // Same pose: 90° about z (q = [w=cos45, z=sin45]) at (1, 2, 3).
  dir.write("a.txt", "# t x y z qx qy qz qw\n1.5 1 2 3 0 0 0.7071067811865476 0.7071067811865476 0.1 0.2\n");
  dir.write("b.csv", "#t,p,q\n1500000000,1,2,3,0.7071067811865476,0,0,0.7071067811865476\n");
  const Trajectory a = readTrajectory(dir.file("a.txt"));  // extra covariance columns are ignored (UZH-FPV)
  const Trajectory b = readTrajectory(dir.file("b.csv"));
  EXPECT_EQ(a[0].t_ns, 1500000000);
  expectSameTrajectory(a, b, 1e-12);
  EXPECT_LT((a[0].T_w_b.so3() * Vec3(1, 0, 0) - Vec3(0, 1, 0)).norm(), 1e-12);
}

TEST(TrajectoryIo, HostileInputIsAnErrorNamingFileAndLine) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"", "no trajectory rows"},
      {"# only a comment\n", "no trajectory rows"},
      {"1.0 1 2 3 0 0 0\n", ":1: expected 8 columns"},
      {"1.0 1 2 3 0 0 0 1\n0.5 1 2 3 0 0 0 1\n", ":2: decreasing"},
      {"1.0 nan 2 3 0 0 0 1\n", "finite number"},
      {"1.0 1 2 3 0 0 0 2\n", "quaternion norm"},
      {"abc 1 2 3 0 0 0 1\n", "time in seconds"},
      {"1,2,3\n", "expected 8 columns"},
      {"1.5,1,2,3,1,0,0,0\n", "non-negative integer"},
      {"\x89PNG\r\n\x1a\n\x00\x00garbage\n", "expected 8 columns"},
      {"100 1 2 3 0 0 0 1\n1e400 1 2 3 0 0 0 1\n", "time in seconds"},
  };
  for (const auto& [text, fragment] : cases) {
    TempDir dir;
    const std::string p = dir.write("t.txt", text);
    SCOPED_TRACE(text);
    test::expectInputError([&] { readTrajectory(p); }, {fragment, p});
  }
  EXPECT_THROW(readTrajectory("/nonexistent/file.txt"), InputError);
}

TEST(TrajectoryIo, EqualTimestampsAreKept) {
  TempDir dir;
  const Trajectory t = readTrajectory(dir.write("t.txt", "1.0 1 2 3 0 0 0 1\n1.0 1 2 4 0 0 0 1\n2.0 0 0 0 0 0 0 1\n"));
  ASSERT_EQ(t.size(), 3u);
  EXPECT_EQ(t[0].t_ns, t[1].t_ns);
}

TEST(TrajectoryIo, ReadsTheSharedRealTrajectories) {
  EDGEVIO_REQUIRE_SHARED_DATA("trajectories");
  for (const char* f : {"trajectories/euroc/V1_02_medium/groundtruth.csv",
                        "trajectories/euroc/V1_02_medium/groundtruth_tum.txt",
                        "trajectories/uzhfpv/indoor_forward_3_groundtruth_tum.txt",
                        "trajectories/tum_vi/room1_groundtruth_tum.txt", "eval_reference/V1_02_estimate_tum.txt"}) {
    const std::string p = test::sharedDataPath(f);
    if (p.empty()) continue;
    const Trajectory t = readTrajectory(p);
    EXPECT_GT(t.size(), 100u) << f;
  }
}

}  // namespace
}  // namespace edgevio::io
