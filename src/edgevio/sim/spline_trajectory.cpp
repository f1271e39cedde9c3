#include "edgevio/sim/spline_trajectory.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include "edgevio/common/time.h"

namespace edgevio::sim {

using geometry::SE3;
using geometry::SO3;

SplineTrajectory::SplineTrajectory(std::int64_t t0_ns, std::int64_t dt_ns, std::vector<SE3> control_points)
    : t0_ns_(t0_ns), dt_ns_(dt_ns), cp_(std::move(control_points)) {
  if (cp_.size() < 4 || dt_ns <= 0) throw std::invalid_argument("SplineTrajectory needs >= 4 control points and dt > 0");
  for (std::size_t k = 0; k + 1 < cp_.size(); ++k) d_.push_back((cp_[k].so3().inverse() * cp_[k + 1].so3()).log());
}

std::int64_t SplineTrajectory::endNs() const {
  return t0_ns_ + static_cast<std::int64_t>(cp_.size() - 3) * dt_ns_;
}

KinematicState SplineTrajectory::evaluate(std::int64_t t_ns) const {
  const double dt = toSeconds(dt_ns_);
  // Segment index and local parameter; times outside the range are clamped.
  const std::int64_t rel = std::clamp<std::int64_t>(t_ns - t0_ns_, 0, endNs() - t0_ns_);
  std::size_t i = static_cast<std::size_t>(rel / dt_ns_);
  double u = static_cast<double>(rel % dt_ns_) / static_cast<double>(dt_ns_);
  if (i + 3 >= cp_.size()) {  // the very end: last segment at u = 1
    i = cp_.size() - 4;
    u = 1.0;
  }
  const double u2 = u * u, u3 = u2 * u;

  // Position: uniform cubic B-spline basis and its derivatives (per second).
  const double b[4] = {(1 - 3 * u + 3 * u2 - u3) / 6, (4 - 6 * u2 + 3 * u3) / 6, (1 + 3 * u + 3 * u2 - 3 * u3) / 6,
                       u3 / 6};
  const double db[4] = {(-3 + 6 * u - 3 * u2) / 6, (-12 * u + 9 * u2) / 6, (3 + 6 * u - 9 * u2) / 6, 3 * u2 / 6};
  const double ddb[4] = {(6 - 6 * u) / 6, (-12 + 18 * u) / 6, (6 - 18 * u) / 6, 6 * u / 6};
  KinematicState s;
  Vec3 p = Vec3::Zero(), v = Vec3::Zero(), a = Vec3::Zero();
  for (int j = 0; j < 4; ++j) {
    const Vec3& c = cp_[i + static_cast<std::size_t>(j)].translation();
    p += b[j] * c;
    v += db[j] * c;
    a += ddb[j] * c;
  }
  s.v_w = v / dt;
  s.a_w = a / (dt * dt);

  // Rotation: cumulative basis B̃_j = Σ_{l≥j} b_l and its time derivative.
  const double bt[3] = {(5 + 3 * u - 3 * u2 + u3) / 6, (1 + 3 * u + 3 * u2 - 2 * u3) / 6, u3 / 6};
  const double dbt[3] = {(3 - 6 * u + 3 * u2) / 6 / dt, (3 + 6 * u - 6 * u2) / 6 / dt, 3 * u2 / 6 / dt};
  SO3 R = cp_[i].so3();
  Vec3 omega = Vec3::Zero();
  for (int j = 0; j < 3; ++j) {
    const Vec3& d = d_[i + static_cast<std::size_t>(j)];
    const SO3 A = SO3::exp(bt[j] * d);
    R = R * A;
    omega = A.inverse() * omega + dbt[j] * d;
  }
  s.T_w_b = SE3(R, p);
  s.omega_b = omega;
  return s;
}

}  // namespace edgevio::sim
