#include "edgevio/imu/preintegration.h"

#include "edgevio/common/time.h"
#include "edgevio/imu/gyro_integration.h"

#include <algorithm>

namespace edgevio::imu {

using geometry::hat;
using geometry::SO3;

Preintegration::Preintegration(const Vec3& b_a, const Vec3& b_g, const ImuNoise& n, Propagation propagation)
    : b_a_(b_a), b_g_(b_g), propagation_(propagation) {
  // Continuous densities σ [unit/√Hz]; the discrete variances σ²/δt (white)
  // and σ²·δt (random walk) are formed in propagate() with each step's δt.
  Q_.block<3, 3>(0, 0) = Mat3::Identity() * n.accel_noise_density * n.accel_noise_density;
  Q_.block<3, 3>(3, 3) = Mat3::Identity() * n.gyro_noise_density * n.gyro_noise_density;
  Q_.block<3, 3>(6, 6) = Mat3::Identity() * n.accel_random_walk * n.accel_random_walk;
  Q_.block<3, 3>(9, 9) = Mat3::Identity() * n.gyro_random_walk * n.gyro_random_walk;
}

void Preintegration::integrate(double dt, const Vec3& acc0, const Vec3& gyr0, const Vec3& acc1, const Vec3& gyr1) {
  const Reading m{dt, acc0, gyr0, acc1, gyr1};
  if (propagation_ == Propagation::kFull) readings_.push_back(m);
  propagate(m);
}

void Preintegration::repropagate(const Vec3& b_a, const Vec3& b_g) {
  b_a_ = b_a;
  b_g_ = b_g;
  dt_sum_ = 0.0;
  alpha_ = beta_ = Vec3::Zero();
  gamma_ = SO3();
  P_.setZero();
  J_.setIdentity();
  for (const Reading& m : readings_) propagate(m);
}

void Preintegration::propagate(const Reading& m) {
  const double dt = m.dt;
  const Vec3 w = 0.5 * (m.gyr0 + m.gyr1) - b_g_;  // ω̃, midpoint
  const SO3 dR = SO3::exp(w * dt);
  const SO3 gamma_next = gamma_ * dR;
  const Vec3 a0 = gamma_ * (m.acc0 - b_a_), a1 = gamma_next * (m.acc1 - b_a_);
  const Vec3 a_mid = 0.5 * (a0 + a1);
  if (propagation_ == Propagation::kFull) propagateCovariance(m, w, dR);
  alpha_ += beta_ * dt + 0.5 * a_mid * dt * dt;
  beta_ += a_mid * dt;
  gamma_ = gamma_next;
  dt_sum_ += dt;
}

void Preintegration::propagateCovariance(const Reading& m, const Vec3& w, const SO3& dR) {
  const double dt = m.dt;
  const Mat3 R = gamma_.matrix();
  const Vec3 a_body = 0.5 * (m.acc0 + m.acc1) - b_a_;  // ã in the body frame of step k
  // Error-state transition (Forster et al. 2017, eqs 58-62, with this step's
  // rotation R = γ_k and midpoint readings):
  //   δα' = δα + δβ δt − ½R hat(ã) δt² δθ − ½R δt² δb_a + ½R δt² n_a
  //   δθ' = ΔRᵀ δθ − Jr δt δb_g + Jr δt n_g
  //   δβ' = δβ − R hat(ã) δt δθ − R δt δb_a + R δt n_a
  //   δb' = δb + δt n_b
  Mat15 F = Mat15::Identity();
  const Mat3 Jr = SO3::rightJacobian(w * dt);
  F.block<3, 3>(kP, kR) = -0.5 * R * hat(a_body) * dt * dt;
  F.block<3, 3>(kP, kV) = Mat3::Identity() * dt;
  F.block<3, 3>(kP, kBa) = -0.5 * R * dt * dt;
  F.block<3, 3>(kR, kR) = dR.matrix().transpose();
  F.block<3, 3>(kR, kBg) = -Jr * dt;
  F.block<3, 3>(kV, kR) = -R * hat(a_body) * dt;
  F.block<3, 3>(kV, kBa) = -R * dt;
  Eigen::Matrix<double, 15, 12> G = Eigen::Matrix<double, 15, 12>::Zero();
  G.block<3, 3>(kP, 0) = 0.5 * R * dt * dt;
  G.block<3, 3>(kR, 3) = Jr * dt;
  G.block<3, 3>(kV, 0) = R * dt;
  G.block<3, 3>(kBa, 6) = Mat3::Identity() * dt;
  G.block<3, 3>(kBg, 9) = Mat3::Identity() * dt;
  // Discrete noise: white noise variance σ²/δt, random-walk increments σ²/δt per unit time.
  const Eigen::Matrix<double, 12, 12> Qd = Q_ / dt;
  P_ = F * P_ * F.transpose() + G * Qd * G.transpose();
  J_ = F * J_;
}

Vec15 Preintegration::residual(const NavState& i, const NavState& j, Mat15* J_i, Mat15* J_j) const {
  const double T = dt_sum_;
  const Vec3 g = gravity();
  const Vec3 dba = i.b_a - b_a_, dbg = i.b_g - b_g_;
  const Mat3 Ja_ba = J_.block<3, 3>(kP, kBa), Ja_bg = J_.block<3, 3>(kP, kBg);
  const Mat3 Jb_ba = J_.block<3, 3>(kV, kBa), Jb_bg = J_.block<3, 3>(kV, kBg);
  const Mat3 Jg_bg = J_.block<3, 3>(kR, kBg);
  // First-order bias correction of the deltas.
  const Vec3 alpha = alpha_ + Ja_ba * dba + Ja_bg * dbg;
  const Vec3 beta = beta_ + Jb_ba * dba + Jb_bg * dbg;
  const SO3 gamma = gamma_ * SO3::exp(Jg_bg * dbg);

  const Mat3 RiT = i.R_w_b.inverse().matrix();
  const Vec3 dp = RiT * (j.p_w - i.p_w - i.v_w * T + 0.5 * g * T * T);
  const Vec3 dv = RiT * (j.v_w - i.v_w + g * T);
  const SO3 E = gamma.inverse() * i.R_w_b.inverse() * j.R_w_b;
  Vec15 r;
  r.segment<3>(kP) = dp - alpha;
  r.segment<3>(kR) = E.log();
  r.segment<3>(kV) = dv - beta;
  r.segment<3>(kBa) = j.b_a - i.b_a;
  r.segment<3>(kBg) = j.b_g - i.b_g;

  const Mat3 JrInv = SO3::rightJacobianInverse(r.segment<3>(kR));
  if (J_i) {
    // (R Exp(δθ))ᵀ y ≈ Rᵀy + hat(Rᵀy) δθ; γ̂ᵀ Exp(−δθ) X = E Exp(−R_jᵀR_i δθ).
    J_i->setZero();
    J_i->block<3, 3>(kP, kP) = -RiT;
    J_i->block<3, 3>(kP, kR) = hat(dp);
    J_i->block<3, 3>(kP, kV) = -RiT * T;
    J_i->block<3, 3>(kP, kBa) = -Ja_ba;
    J_i->block<3, 3>(kP, kBg) = -Ja_bg;
    J_i->block<3, 3>(kR, kR) = -JrInv * (j.R_w_b.inverse() * i.R_w_b).matrix();
    // γ̂(δb_g + ε) ≈ γ̂·Exp(Jr(Jg δb_g)·Jg·ε): r_θ gains −Jr⁻¹(r_θ)·Eᵀ·Jr(Jg δb_g)·Jg·ε.
    J_i->block<3, 3>(kR, kBg) = -JrInv * E.inverse().matrix() * SO3::rightJacobian(Jg_bg * dbg) * Jg_bg;
    J_i->block<3, 3>(kV, kR) = hat(dv);
    J_i->block<3, 3>(kV, kV) = -RiT;
    J_i->block<3, 3>(kV, kBa) = -Jb_ba;
    J_i->block<3, 3>(kV, kBg) = -Jb_bg;
    J_i->block<3, 3>(kBa, kBa) = -Mat3::Identity();
    J_i->block<3, 3>(kBg, kBg) = -Mat3::Identity();
  }
  if (J_j) {
    J_j->setZero();
    J_j->block<3, 3>(kP, kP) = RiT;
    J_j->block<3, 3>(kR, kR) = JrInv;
    J_j->block<3, 3>(kV, kV) = RiT;
    J_j->block<3, 3>(kBa, kBa) = Mat3::Identity();
    J_j->block<3, 3>(kBg, kBg) = Mat3::Identity();
  }
  return r;
}

std::optional<Preintegration> preintegrate(const std::vector<ImuSample>& imu, std::int64_t t0, std::int64_t t1,
                                           const Vec3& b_a, const Vec3& b_g, const ImuNoise& noise, double max_gap_s,
                                           Propagation propagation) {
  if (imuGapWithin(imu, t0, t1, max_gap_s)) return std::nullopt;
  Preintegration p(b_a, b_g, noise, propagation);
  const bool covered = forEachImuInterval(imu, t0, t1, [&](double dt, const Vec3& a0, const Vec3& w0, const Vec3& a1, const Vec3& w1) {
    p.integrate(dt, a0, w0, a1, w1);
  });
  if (!covered) return std::nullopt;
  return p;
}

NavState predictState(const NavState& r, const Preintegration& pre) {
  // Deltas corrected to first order for r's biases (as in the residual).
  const Vec3 dba = r.b_a - pre.linearizationBa(), dbg = r.b_g - pre.linearizationBg();
  const Mat15& J = pre.jacobian();
  const Vec3 alpha = pre.alpha() + J.block<3, 3>(kP, kBa) * dba + J.block<3, 3>(kP, kBg) * dbg;
  const Vec3 beta = pre.beta() + J.block<3, 3>(kV, kBa) * dba + J.block<3, 3>(kV, kBg) * dbg;
  const geometry::SO3 gamma = pre.gamma() * geometry::SO3::exp(J.block<3, 3>(kR, kBg) * dbg);
  const double T = pre.deltaT();
  NavState n = r;
  n.R_w_b = r.R_w_b * gamma;
  n.p_w = r.p_w + r.v_w * T - 0.5 * gravity() * T * T + (r.R_w_b * alpha);
  n.v_w = r.v_w - gravity() * T + (r.R_w_b * beta);
  return n;
}

}  // namespace edgevio::imu
