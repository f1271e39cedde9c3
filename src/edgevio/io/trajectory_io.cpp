#include "edgevio/io/trajectory_io.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <memory>

#include "edgevio/common/error.h"
#include "edgevio/common/table_reader.h"
#include "edgevio/io/bag_sequence.h"
#include "edgevio/io/rosbag.h"

namespace edgevio::io {

namespace {

TrajectoryFormat detectFormat(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot open trajectory file for reading (check the path)");
  std::string line;
  while (std::getline(in, line)) {
    const auto b = line.find_first_not_of(" \t\r");
    if (b == std::string::npos || line[b] == '#') continue;
    return line.find(',') != std::string::npos ? TrajectoryFormat::kEuroc : TrajectoryFormat::kTum;
  }
  throw InputError(path, 0, "no trajectory rows: expected TUM (t x y z qx qy qz qw) or EuRoC CSV (t_ns,px,...,qw,qx,qy,qz)");
}

Quat readUnitQuaternion(const TableReader& r, double w, double x, double y, double z) {
  const Quat q(w, x, y, z);
  const double n = q.norm();
  if (std::abs(n - 1.0) > 0.01)
    r.fail("quaternion norm is " + std::to_string(n) + ", expected 1 (check the column order: TUM is qx qy qz qw, "
           "EuRoC is qw,qx,qy,qz)");
  return q.normalized();
}

}  // namespace

Trajectory readTrajectory(const std::string& path, TrajectoryFormat* detected) {
  if (RosbagReader::looksLikeBag(path)) return readBagTrajectory(path);
  const TrajectoryFormat format = detectFormat(path);
  if (detected) *detected = format;
  const bool euroc = format == TrajectoryFormat::kEuroc;
  TableReader r(path, euroc ? TableReader::Separator::kComma : TableReader::Separator::kWhitespace);
  Trajectory traj;
  while (r.next()) {
    TrajectorySample s;
    if (euroc) {
      r.requireFields(8, "t_ns,px,py,pz,qw,qx,qy,qz");
      s.t_ns = r.integer(0);
      s.T_w_b = geometry::SE3(readUnitQuaternion(r, r.number(4), r.number(5), r.number(6), r.number(7)),
                              Vec3(r.number(1), r.number(2), r.number(3)));
      if (r.size() >= 17) {
        s.v_w = Vec3(r.numberOrNan(8), r.numberOrNan(9), r.numberOrNan(10));
        s.b_g = Vec3(r.numberOrNan(11), r.numberOrNan(12), r.numberOrNan(13));
        s.b_a = Vec3(r.numberOrNan(14), r.numberOrNan(15), r.numberOrNan(16));
      }
    } else {
      r.requireFields(8, "t x y z qx qy qz qw");
      s.t_ns = r.secondsAsNanoseconds(0);
      s.T_w_b = geometry::SE3(readUnitQuaternion(r, r.number(7), r.number(4), r.number(5), r.number(6)),
                              Vec3(r.number(1), r.number(2), r.number(3)));
    }
    // Equal timestamps are accepted: real estimator outputs contain them (the
    // evo reference estimate in shared/data does) and evo keeps them.
    if (!traj.empty() && s.t_ns < traj.back().t_ns)
      r.fail("decreasing timestamp: rows must be in increasing time order");
    traj.push_back(s);
  }
  if (traj.empty()) throw InputError(path, 0, "no trajectory rows found");
  return traj;
}

TrajectoryWriter::TrajectoryWriter(const std::string& path, TrajectoryFormat format, bool velocity_and_bias)
    : file_(std::fopen(path.c_str(), "w")), format_(format), velocity_and_bias_(velocity_and_bias) {
  if (!file_) throw InputError(path, 0, "cannot open file for writing (does the folder exist?)");
  if (format_ == TrajectoryFormat::kTum)
    std::fprintf(file_, "# timestamp[s] tx ty tz qx qy qz qw\n");
  else
    std::fprintf(file_, "#timestamp [ns],p_RS_R_x [m],p_RS_R_y [m],p_RS_R_z [m],q_RS_w [],q_RS_x [],q_RS_y [],q_RS_z []%s\n",
                 velocity_and_bias_ ? ",v_RS_R_x [m s^-1],v_RS_R_y [m s^-1],v_RS_R_z [m s^-1],b_w_RS_S_x [rad s^-1],"
                                      "b_w_RS_S_y [rad s^-1],b_w_RS_S_z [rad s^-1],b_a_RS_S_x [m s^-2],b_a_RS_S_y [m s^-2],"
                                      "b_a_RS_S_z [m s^-2]"
                                    : "");
}

TrajectoryWriter::~TrajectoryWriter() { std::fclose(file_); }

void TrajectoryWriter::write(const TrajectorySample& s) {
  const Vec3& p = s.T_w_b.translation();
  const Quat& q = s.T_w_b.quaternion();
  ++count_;
  if (format_ == TrajectoryFormat::kTum) {
    std::fprintf(file_, "%lld.%09lld %.9f %.9f %.9f %.9f %.9f %.9f %.9f\n", static_cast<long long>(s.t_ns / 1000000000),
                 static_cast<long long>(s.t_ns % 1000000000), p.x(), p.y(), p.z(), q.x(), q.y(), q.z(), q.w());
    return;
  }
  std::fprintf(file_, "%lld,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f,%.9f", static_cast<long long>(s.t_ns), p.x(), p.y(), p.z(),
               q.w(), q.x(), q.y(), q.z());
  if (velocity_and_bias_) {
    if (s.hasVelocityAndBias())
      std::fprintf(file_, ",%.9f,%.9f,%.9f,%.9g,%.9g,%.9g,%.9g,%.9g,%.9g", s.v_w.x(), s.v_w.y(), s.v_w.z(), s.b_g.x(),
                   s.b_g.y(), s.b_g.z(), s.b_a.x(), s.b_a.y(), s.b_a.z());
    else
      std::fprintf(file_, ",nan,nan,nan,nan,nan,nan,nan,nan,nan");
  }
  std::fprintf(file_, "\n");
}

void writeTrajectoryTum(const std::string& path, const Trajectory& trajectory) {
  TrajectoryWriter w(path, TrajectoryFormat::kTum);
  for (const auto& s : trajectory) w.write(s);
}

void writeTrajectoryEuroc(const std::string& path, const Trajectory& trajectory) {
  bool full = !trajectory.empty();
  for (const auto& s : trajectory) full = full && s.hasVelocityAndBias();
  TrajectoryWriter w(path, TrajectoryFormat::kEuroc, full);
  for (const auto& s : trajectory) w.write(s);
}

}  // namespace edgevio::io
