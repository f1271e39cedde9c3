#pragma once
// A smooth continuous-time trajectory T_w_b(t) with analytic derivatives, for
// rendering and IMU synthesis (issue #4).
//
// Position: uniform cubic B-spline in R³ (C², so acceleration is continuous).
// Rotation: cumulative cubic B-spline on SO(3) (Kim, Kim and Shin 1995;
// Sommer et al., "Efficient derivative computation for cumulative B-splines on
// Lie groups", CVPR 2020):
//   R(u) = R_i · Π_{j=1..3} exp(B̃_j(u) d_j),  d_j = log(R_{i+j−1}⁻¹ R_{i+j}),
//   B̃_1 = (5 + 3u − 3u² + u³)/6,  B̃_2 = (1 + 3u + 3u² − 2u³)/6,  B̃_3 = u³/6.
// Body angular velocity (R⁻¹Ṙ = hat(ω)) by the recursion
//   ω ← A_jᵀ ω + (dB̃_j/dt) d_j,  A_j = exp(B̃_j d_j),  j = 1..3, ω = 0 initially.
// Control point k sits at time t0 + (k − 1)·dt; the spline is defined on
// [t0, t0 + (N − 3)·dt] for N control points.
#include <cstdint>
#include <vector>

#include "edgevio/geometry/se3.h"

namespace edgevio::sim {

struct KinematicState {
  geometry::SE3 T_w_b;
  Vec3 v_w = Vec3::Zero();      ///< velocity in world [m/s]
  Vec3 a_w = Vec3::Zero();      ///< acceleration in world [m/s²]
  Vec3 omega_b = Vec3::Zero();  ///< angular velocity in body [rad/s]
};

class SplineTrajectory {
 public:
  SplineTrajectory() = default;
  /// Control points are the given poses at t0, t0 + dt, ...; see header comment.
  SplineTrajectory(std::int64_t t0_ns, std::int64_t dt_ns, std::vector<geometry::SE3> control_points);

  std::int64_t beginNs() const { return t0_ns_; }
  std::int64_t endNs() const;
  KinematicState evaluate(std::int64_t t_ns) const;
  geometry::SE3 pose(std::int64_t t_ns) const { return evaluate(t_ns).T_w_b; }

 private:
  std::int64_t t0_ns_ = 0, dt_ns_ = 1;
  std::vector<geometry::SE3> cp_;
  std::vector<Vec3> d_;  // d_[k] = log(R_k⁻¹ R_{k+1})
};

}  // namespace edgevio::sim
