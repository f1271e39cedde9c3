#pragma once
// The one trajectory file reader and writer.
//  TUM:   `t[s] x y z qx qy qz qw` (whitespace separated; extra columns ignored)
//  EuRoC: `t[ns],px,py,pz,qw,qx,qy,qz[,vx,vy,vz,bwx,bwy,bwz,bax,bay,baz]`
// The format is detected from the first data row: commas mean EuRoC.
#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "edgevio/geometry/se3.h"

namespace edgevio::io {

struct TrajectorySample {
  std::int64_t t_ns = 0;
  geometry::SE3 T_w_b;
  /// Velocity and biases, present in EuRoC ground truth; NaN when unknown.
  Vec3 v_w = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Vec3 b_g = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  Vec3 b_a = Vec3::Constant(std::numeric_limits<double>::quiet_NaN());
  bool hasVelocityAndBias() const { return v_w.allFinite() && b_g.allFinite() && b_a.allFinite(); }
};
using Trajectory = std::vector<TrajectorySample>;

enum class TrajectoryFormat { kTum, kEuroc };

/// Reads a trajectory; timestamps must not decrease (equal ones are kept, as evo
/// does), quaternions must be unit to 1 % (they are normalised). Throws
/// InputError naming file and line. A ROS bag gives its only pose topic
/// (io/bag_sequence.h; `detected` is then left as it was).
Trajectory readTrajectory(const std::string& path, TrajectoryFormat* detected = nullptr);

/// Writes a trajectory sample by sample, so that a run of any length keeps
/// none of it in memory: TUM with nanosecond-exact timestamps (9 decimals), or
/// EuRoC CSV, with velocity and bias columns if asked for ("nan" in them for
/// a sample that has none; readTrajectory reads that back as unknown).
class TrajectoryWriter {
 public:
  TrajectoryWriter(const std::string& path, TrajectoryFormat format, bool velocity_and_bias = false);
  ~TrajectoryWriter();
  TrajectoryWriter(const TrajectoryWriter&) = delete;
  TrajectoryWriter& operator=(const TrajectoryWriter&) = delete;
  void write(const TrajectorySample& sample);
  std::size_t count() const { return count_; }

 private:
  std::FILE* file_ = nullptr;
  TrajectoryFormat format_;
  bool velocity_and_bias_;
  std::size_t count_ = 0;
};

/// Writes TUM (see TrajectoryWriter).
void writeTrajectoryTum(const std::string& path, const Trajectory& trajectory);
/// Writes EuRoC CSV; velocity and bias columns when every sample has them.
void writeTrajectoryEuroc(const std::string& path, const Trajectory& trajectory);

}  // namespace edgevio::io
