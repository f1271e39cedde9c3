#include "edgevio/estimator/sliding_window.h"

#include "edgevio/estimator/block_cholesky.h"

#include <Eigen/Cholesky>
#include <algorithm>
#include <cmath>
#include <map>

namespace edgevio::estimator {

using geometry::SO3;
using imu::NavState;
using imu::Vec15;
using Eigen::MatrixXd;
using Eigen::VectorXd;

NavState boxplus(const NavState& x, const Eigen::Ref<const Vec15>& d) {
  NavState o = x;
  o.p_w += d.segment<3>(imu::kP);
  o.R_w_b = x.R_w_b * SO3::exp(d.segment<3>(imu::kR));
  o.v_w += d.segment<3>(imu::kV);
  o.b_a += d.segment<3>(imu::kBa);
  o.b_g += d.segment<3>(imu::kBg);
  return o;
}

Vec15 boxminus(const NavState& x, const NavState& x0) {
  Vec15 d;
  d.segment<3>(imu::kP) = x.p_w - x0.p_w;
  d.segment<3>(imu::kR) = (x0.R_w_b.inverse() * x.R_w_b).log();
  d.segment<3>(imu::kV) = x.v_w - x0.v_w;
  d.segment<3>(imu::kBa) = x.b_a - x0.b_a;
  d.segment<3>(imu::kBg) = x.b_g - x0.b_g;
  return d;
}

CalibrationState boxplus(const CalibrationState& c, const Eigen::Ref<const Vec15>& d) {
  CalibrationState o = c;
  o.time_offset_s += d(kCalibTimeOffset);
  o.R_correction = c.R_correction * SO3::exp(d.segment<3>(kCalibRotation));
  o.t_correction = c.t_correction + c.R_correction * d.segment<3>(kCalibTranslation);
  return o;
}

Vec15 boxminus(const CalibrationState& c, const CalibrationState& c0) {
  Vec15 d = Vec15::Zero();
  d(kCalibTimeOffset) = c.time_offset_s - c0.time_offset_s;
  d.segment<3>(kCalibRotation) = (c0.R_correction.inverse() * c.R_correction).log();
  d.segment<3>(kCalibTranslation) = c0.R_correction.inverse() * (c.t_correction - c0.t_correction);
  return d;
}

geometry::SE3 cameraExtrinsics(const Window& w) {
  if (!w.calibration) return w.T_b_c;
  return w.T_b_c * geometry::SE3(w.calibration->R_correction, w.calibration->t_correction);
}

namespace {

// Added to an inertial link's covariance so that a zero-length link still has
// a finite information matrix; about 1 % of the smallest variance a 50 ms link
// carries (its gyroscope bias walk: (2 x 1.94e-5)^2 x 0.05 = 7.5e-11 at EuRoC's density).
constexpr double kCovarianceFloor = 1e-12;
// Added to the marginalised state's block before it is inverted: a direction
// no link informs (a bias never excited) stays finite, while every informed
// one (information >= 1e-4: variances of at most 1e4) is untouched.
constexpr double kMarginalRegulariser = 1e-12;
// The gauge prior's stiffness relative to H's largest diagonal entry: a step
// along a gauge direction shrinks to about 1e-3 of the unconstrained one,
// while H stays far from double precision's limits (1e3 of 1e16).
constexpr double kGaugeStiffness = 1e3;
// A Gauss-Newton step of this norm (m, rad, m/s and bias units together)
// moves no state measurably: the solve has converged.
constexpr double kNegligibleStep = 1e-9;
// The perturbed Cholesky grows λ tenfold per attempt: 20 attempts reach 1e20
// times the first, more than any finite H needs.
constexpr int kDampingAttempts = 20;
constexpr double kDampingGrowth = 10.0;

imu::Mat15 inertialInformation(const imu::Preintegration& p) {
  const imu::Mat15 P = p.covariance() + imu::Mat15::Identity() * kCovarianceFloor;
  return P.ldlt().solve(imu::Mat15::Identity());
}

}  // namespace

InertialLink::InertialLink(std::size_t from, std::size_t to, imu::Preintegration preintegration)
    : i(from), j(to), pre(std::move(preintegration)), information(inertialInformation(pre)) {}

void InertialLink::repropagate(const Vec3& b_a, const Vec3& b_g) {
  pre.repropagate(b_a, b_g);
  information = inertialInformation(pre);
}

namespace {

/// Normal equations H δ = −g over a set of states (local indices via `slot`).
struct Normal {
  MatrixXd H;
  VectorXd g;
  double cost = 0.0;
  bool cost_only = false;  ///< only the cost: no Jacobians, no H or g (windowCost)
  explicit Normal(std::size_t n, bool only_cost = false)
      : H(only_cost ? MatrixXd() : MatrixXd::Zero(15 * static_cast<long>(n), 15 * static_cast<long>(n))),
        g(only_cost ? VectorXd() : VectorXd::Zero(15 * static_cast<long>(n))),
        cost_only(only_cost) {}

  /// Back to zero, keeping the memory (a window's H is 1.6 MB).
  void reset() {
    H.setZero();
    g.setZero();
    cost = 0.0;
  }

  /// Adds to the (δp, δθ) rows and columns of blocks a, b (a visual term's only ones).
  void addPose(long a, long b, const Mat6& Hab) { H.block<6, 6>(15 * a, 15 * b) += Hab; }

  template <int R>
  void add(const Eigen::Matrix<double, R, 1>& r, const Eigen::Matrix<double, R, R>& W,
           const std::vector<std::pair<long, Eigen::Matrix<double, R, 15>>>& blocks) {
    cost += 0.5 * r.dot(W * r);
    if (cost_only) return;
    for (std::size_t u = 0; u < blocks.size(); ++u) {
      const auto& [a, Ja] = blocks[u];
      // lazyProduct: small fixed sizes, where Eigen's general product mostly packs.
      const Eigen::Matrix<double, 15, R> JaT_W = Ja.transpose().lazyProduct(W);
      g.segment<15>(15 * a) += JaT_W * r;
      for (std::size_t v = u; v < blocks.size(); ++v) {
        const auto& [b, Jb] = blocks[v];
        const imu::Mat15 Hab = JaT_W.lazyProduct(Jb);
        H.block<15, 15>(15 * a, 15 * b) += Hab;
        if (v != u) H.block<15, 15>(15 * b, 15 * a) += Hab.transpose();
      }
    }
  }
};

/// The links from one reference state r_i = b + e_i: b the error they share
/// (covariance Σ_s = shared × their mean covariance), e_i each one's own
/// (information W_i, Huber-weighted). Their joint information, with
/// D = diag(W_i⁻¹) and U = [I … I]ᵀ, is (D + U Σ_s Uᵀ)⁻¹ = diag(W_i) −
/// [W_i] M⁻¹ [W_j] with M = Σ_s⁻¹ + Σ W_i (Woodbury). The links add their
/// diag(W_i) terms themselves; this subtracts the rest: ½ sᵀM⁻¹s from the
/// cost with s = Σ W_i r_i, and with B_a = Σ W_i ∂r_i/∂x_a over the links
/// on block a, B_aᵀM⁻¹s from g_a and B_aᵀM⁻¹B_b from H_ab. A lone link's
/// information comes out as the link's own: ((1 − shared)Σ + shared·Σ)⁻¹.
/// Groups form among the links linearised together: marginalisation takes
/// the leaving state's links, so each goes into the prior with its whole
/// covariance, as if independent of the links that stay (unless
/// front_marginalization_drops_links drops those of a frame removed in front).
struct SharedError {
  // A visual residual depends on a state's δp and δθ (columns 0-5) and on the
  // calibration's time offset, rotation and translation (columns 0-6) only.
  static constexpr int kColumns = 7;
  static_assert(imu::kR + 3 <= kColumns && kCalibTranslation + 3 <= kColumns);
  using Mat6x7 = Eigen::Matrix<double, 6, kColumns>;

  Vec6 s = Vec6::Zero();
  Mat6 sum_W = Mat6::Zero(), sum_covariance = Mat6::Zero();
  int links = 0;
  std::map<long, Mat6x7> B;

  void add(const Vec6& r, const Mat6& W, const Mat6& covariance) {
    s += W * r;
    sum_W += W;
    sum_covariance += covariance;
    ++links;
  }
  void addJacobian(long block, const Mat6& W, const Mat6x15& J) {
    const Mat6x7 WJ = W.lazyProduct(J.leftCols<kColumns>());
    const auto [it, inserted] = B.try_emplace(block, WJ);
    if (!inserted) it->second += WJ;
  }
  void subtract(double shared, Normal* n) const {
    const Mat6 shared_covariance = shared / links * sum_covariance;
    const Mat6 M = shared_covariance.ldlt().solve(Mat6::Identity()) + sum_W;
    const Eigen::LDLT<Mat6> M_ldlt(M);
    const Vec6 Ms = M_ldlt.solve(s);
    n->cost -= 0.5 * s.dot(Ms);
    if (n->cost_only) return;
    for (const auto& [a, Ba] : B) {
      n->g.segment<kColumns>(15 * a) -= Ba.transpose() * Ms;
      const Mat6x7 MBa = M_ldlt.solve(Ba);
      for (const auto& [b, Bb] : B) n->H.block<kColumns, kColumns>(15 * b, 15 * a) -= Bb.transpose().lazyProduct(MBa);
    }
  }
};

/// Whether the window weighs a link by its edge residuals (Coupling::kTight).
bool isTight(const Window& w, const VisualLink& l) { return l.image && !w.states[l.r].points.empty(); }

/// One keyframe's tight links as linearised: its points' system over the
/// links' twists, and each twist's Jacobians with respect to the (δp, δθ) of
/// the keyframe's state (A) and of the frame's (B): ξ_a = A_a δx_r + B_a δx_{n_a}.
struct StructureGroup {
  std::size_t reference = 0;
  std::vector<std::size_t> frames;
  std::vector<Mat6> A, B;
  StructureSystem system;
};

/// Where a state's Jacobians are evaluated: its first estimate (the prior's
/// linearisation point) when it is in the prior and first-estimate Jacobians
/// are on, otherwise its current estimate.
std::vector<const NavState*> jacobianPoints(const Window& w, const EstimatorOptions& o) {
  std::vector<const NavState*> at(w.states.size());
  for (std::size_t i = 0; i < w.states.size(); ++i) at[i] = &w.states[i].x;
  if (o.first_estimate_jacobians)
    for (std::size_t k = 0; k < w.prior.states.size(); ++k) at[w.prior.states[k]] = &w.prior.x0[k];
  return at;
}

/// The state as the camera saw it: the body at IMU time t_ns + the
/// calibration's time offset, i.e. moved along its velocity and bias-corrected
/// gyroscope reading over the offset's change since its inertial link was
/// integrated (first order, as VINS-Fusion's feature-velocity correction).
NavState atCaptureTime(const WindowState& s, const NavState& x, const CalibrationState& c) {
  const double dt = c.time_offset_s - s.time_offset_s;
  NavState o = x;
  o.R_w_b = x.R_w_b * SO3::exp((s.gyro - x.b_g) * dt);
  o.p_w = x.p_w + x.v_w * dt;
  return o;
}

/// A visual link's residual at states xr, xn (of w.states[l.r], [l.n]) and the
/// window's calibration, with Jacobians for the states and the calibration
/// block. ∂r/∂t of the time offset: the states' twists (Rᵀv, ω) through their
/// Jacobians, whose δp columns are ∂r/∂ρ·Rᵀ, so ∂r/∂ρ·Rᵀv = J_δp·v.
Vec6 visualResidual(const Window& w, const VisualLink& l, const NavState& xr, const NavState& xn, Mat6x15* Jr, Mat6x15* Jn,
                    Mat6x15* Jc) {
  if (!w.calibration) return relativePoseResidual(l.link.T_nr, xr, xn, w.T_b_c, Jr, Jn);
  const CalibrationState& c = *w.calibration;
  const NavState r = atCaptureTime(w.states[l.r], xr, c), n = atCaptureTime(w.states[l.n], xn, c);
  Mat6 J_extrinsics;
  const Vec6 res = relativePoseResidual(l.link.T_nr, r, n, cameraExtrinsics(w), Jr, Jn, Jc ? &J_extrinsics : nullptr);
  if (Jc) {
    Jc->setZero();
    const auto twistColumn = [](const Mat6x15& J, const NavState& x, const WindowState& s) -> Vec6 {
      return J.block<6, 3>(0, imu::kP) * x.v_w + J.block<6, 3>(0, imu::kR) * (s.gyro - x.b_g);
    };
    if (c.time_offset) Jc->col(kCalibTimeOffset) = twistColumn(*Jr, r, w.states[l.r]) + twistColumn(*Jn, n, w.states[l.n]);
    if (c.rotation) Jc->block<6, 3>(0, kCalibRotation) = J_extrinsics.rightCols<3>();
    if (c.translation) Jc->block<6, 3>(0, kCalibTranslation) = J_extrinsics.leftCols<3>();
  }
  return res;
}

/// Adds the edge residuals of state `reference`'s points in the frames of its
/// tight `links` (keyframe_structure.h), the inverse depths eliminated, to the
/// normal equations: H_states += Jᵀ H_ξ J and g_states += Jᵀ g_ξ with ξ = J δx.
/// The twists' Jacobians are those of relativePoseResidual at a zero residual
/// (measured = predicted: Jr⁻¹ = I), at the states' Jacobian points.
void addStructure(const Window& w, const EstimatorOptions& o, const std::vector<const NavState*>& jp,
                  const std::map<std::size_t, long>& slot, std::size_t reference, const std::vector<const VisualLink*>& links,
                  Normal* n, std::vector<StructureGroup>* groups) {
  const geometry::SE3 T_b_c = cameraExtrinsics(w);
  StructureGroup grp;
  grp.reference = reference;
  std::vector<StructureLink> at;
  for (const VisualLink* l : links) {
    at.push_back({predictedRelativePose(w.states[l->r].x, w.states[l->n].x, T_b_c), l->image.get()});
    grp.frames.push_back(l->n);
  }
  grp.system = linearizeStructure(w.states[reference].points, at, {o.tight_pixel_sigma_px, o.tight_huber_px}, n->cost_only);
  n->cost += grp.system.cost;
  if (n->cost_only) return;
  for (const std::size_t f : grp.frames) {
    Mat6x15 Jr, Jn;
    relativePoseResidual(predictedRelativePose(*jp[reference], *jp[f], T_b_c), *jp[reference], *jp[f], T_b_c, &Jr, &Jn);
    grp.A.push_back(Jr.leftCols<6>());
    grp.B.push_back(Jn.leftCols<6>());
  }
  const long sr = slot.at(reference);
  for (std::size_t a = 0; a < grp.frames.size(); ++a) {
    const long la = static_cast<long>(a), na = slot.at(grp.frames[a]);
    const Vec6 ga = grp.system.g.segment<6>(6 * la);
    n->g.segment<6>(15 * sr) += grp.A[a].transpose() * ga;
    n->g.segment<6>(15 * na) += grp.B[a].transpose() * ga;
    for (std::size_t b = 0; b < grp.frames.size(); ++b) {
      const long nb = slot.at(grp.frames[b]);
      const Mat6 Hab = grp.system.H.block<6, 6>(6 * la, 6 * static_cast<long>(b));
      const Mat6 AH = grp.A[a].transpose() * Hab, BH = grp.B[a].transpose() * Hab;
      n->addPose(sr, sr, AH * grp.A[b]);
      n->addPose(sr, nb, AH * grp.B[b]);
      n->addPose(na, sr, BH * grp.A[b]);
      n->addPose(na, nb, BH * grp.B[b]);
    }
  }
  if (groups) groups->push_back(std::move(grp));
}

/// The calibration file's prior on the calibration block (CalibrationState):
/// ½(δ/σ)² per estimated direction, unit information on the others.
void addCalibrationPrior(const CalibrationState& c, long slot, Normal* n) {
  const Vec15 d = boxminus(c, CalibrationState{});
  Vec15 info = Vec15::Ones();
  info(kCalibTimeOffset) = c.time_offset ? 1.0 / (c.time_offset_sigma_s * c.time_offset_sigma_s) : 1.0;
  info.segment<3>(kCalibRotation).setConstant(c.rotation ? 1.0 / (c.rotation_sigma_rad * c.rotation_sigma_rad) : 1.0);
  info.segment<3>(kCalibTranslation)
      .setConstant(c.translation ? 1.0 / (c.translation_sigma_m * c.translation_sigma_m) : 1.0);
  n->cost += 0.5 * d.dot(info.cwiseProduct(d));
  if (n->cost_only) return;
  n->g.segment<15>(15 * slot) += info.cwiseProduct(d);
  n->H.block<15, 15>(15 * slot, 15 * slot).diagonal() += info;
}

/// Which priors linearize adds beside the links: both (the whole window's
/// cost), the marginalisation's only (the calibration file's prior is never
/// folded into it), or none (its states are not in `slot`).
enum class Priors { kBoth, kMarginal, kNone };

/// Adds the factors selected by the predicates, with local indices from
/// `slot` and the calibration block (with the window's calibration) at
/// `calib_slot`, and the `priors`.
/// Tight links are grouped by keyframe among those `use_visual` takes; with
/// `groups`, their linearisation is kept for the points' back-substitution.
template <class UseInertial, class UseVisual>
void linearize(const Window& w, const EstimatorOptions& o, const std::map<std::size_t, long>& slot, long calib_slot,
               Priors priors, UseInertial use_inertial, UseVisual use_visual, Normal* n,
               std::vector<StructureGroup>* groups = nullptr) {
  const std::vector<const NavState*> jp = jacobianPoints(w, o);
  // Jacobians in the residual's own call when they are taken at the estimate,
  // in a second call at the first estimates otherwise.
  const auto elsewhere = [&](std::size_t a, std::size_t b) {
    return !n->cost_only && (jp[a] != &w.states[a].x || jp[b] != &w.states[b].x);
  };
  for (const InertialLink& l : w.inertial) {
    if (!use_inertial(l)) continue;
    imu::Mat15 Ji, Jj;
    const bool fej = elsewhere(l.i, l.j), here = !n->cost_only && !fej;
    const Vec15 r = l.pre.residual(w.states[l.i].x, w.states[l.j].x, here ? &Ji : nullptr, here ? &Jj : nullptr);
    if (fej) l.pre.residual(*jp[l.i], *jp[l.j], &Ji, &Jj);
    n->add<15>(r, l.information, {{slot.at(l.i), Ji}, {slot.at(l.j), Jj}});
  }
  const double shared = o.visual_shared_fraction;
  std::map<std::size_t, SharedError> by_reference;  // the links of each reference state, when they share an error
  std::map<std::size_t, std::vector<const VisualLink*>> tight_by_reference;
  for (const VisualLink& l : w.visual) {
    if (!use_visual(l)) continue;
    if (isTight(w, l)) {
      tight_by_reference[l.r].push_back(&l);
      continue;
    }
    Mat6x15 Jr, Jn, Jc;
    const bool fej = elsewhere(l.r, l.n), here = !n->cost_only && !fej;
    Mat6x15* Jc_here = w.calibration && here ? &Jc : nullptr;
    const Vec6 r = visualResidual(w, l, w.states[l.r].x, w.states[l.n].x, here ? &Jr : nullptr, here ? &Jn : nullptr, Jc_here);
    if (fej) visualResidual(w, l, *jp[l.r], *jp[l.n], &Jr, &Jn, w.calibration ? &Jc : nullptr);
    // With a shared part, the information of the link's own part, (1 − shared)⁻¹ times the link's.
    const Mat6 own = shared > 0 ? Mat6(l.link.information / (1.0 - shared)) : l.link.information;
    const Mat6 W = huberWeightedInformation(own, r, o.huber_translation_m, o.huber_rotation_deg * kDegToRad);
    if (w.calibration)
      n->add<6>(r, W, {{slot.at(l.r), Jr}, {slot.at(l.n), Jn}, {calib_slot, Jc}});
    else
      n->add<6>(r, W, {{slot.at(l.r), Jr}, {slot.at(l.n), Jn}});
    if (shared > 0) {
      SharedError& e = by_reference[l.r];
      e.add(r, W, l.link.information.ldlt().solve(Mat6::Identity()));
      if (!n->cost_only) {
        e.addJacobian(slot.at(l.r), W, Jr);
        e.addJacobian(slot.at(l.n), W, Jn);
        if (w.calibration) e.addJacobian(calib_slot, W, Jc);
      }
    }
  }
  for (const auto& [reference, e] : by_reference) e.subtract(shared, n);
  for (const auto& [reference, links] : tight_by_reference) addStructure(w, o, jp, slot, reference, links, n, groups);
  if (priors == Priors::kBoth && w.calibration) addCalibrationPrior(*w.calibration, calib_slot, n);
  if (priors != Priors::kNone && !w.prior.empty()) {
    // ½δᵀHδ + bᵀδ at δ = x ⊟ x0: gradient b + Hδ, Hessian H (the Jacobian of
    // ⊟ is taken as identity: first-estimate linearisation of the prior).
    const std::size_t m = w.prior.states.size(), blocks = m + (w.prior.calibration ? 1 : 0);
    VectorXd d(15 * static_cast<long>(blocks));
    std::vector<long> at(blocks);  // the prior's blocks' slots
    for (std::size_t k = 0; k < m; ++k) {
      d.segment<15>(15 * static_cast<long>(k)) = boxminus(w.states[w.prior.states[k]].x, w.prior.x0[k]);
      at[k] = slot.at(w.prior.states[k]);
    }
    if (w.prior.calibration) {
      d.tail<15>() = boxminus(*w.calibration, w.prior.c0);
      at[m] = calib_slot;
    }
    n->cost += 0.5 * d.dot(w.prior.H * d) + w.prior.b.dot(d);
    if (n->cost_only) return;
    const VectorXd grad = w.prior.b + w.prior.H * d;
    for (std::size_t a = 0; a < blocks; ++a) {
      n->g.segment<15>(15 * at[a]) += grad.segment<15>(15 * static_cast<long>(a));
      for (std::size_t b = 0; b < blocks; ++b)
        n->H.block<15, 15>(15 * at[a], 15 * at[b]) +=
            w.prior.H.block<15, 15>(15 * static_cast<long>(a), 15 * static_cast<long>(b));
    }
  }
}

std::map<std::size_t, long> identitySlots(std::size_t n) {
  std::map<std::size_t, long> s;
  for (std::size_t i = 0; i < n; ++i) s[i] = static_cast<long>(i);
  return s;
}

/// Perturbed Cholesky (METHOD.md §5): add λI, growing λ, until H + λI is
/// positive definite; the factorisation exploits the window's envelope.
VectorXd perturbedCholeskySolve(const MatrixXd& H, const VectorXd& rhs, double lambda0) {
  double lambda = lambda0 * std::max(1.0, H.diagonal().cwiseAbs().maxCoeff());
  VectorXd x;
  for (int attempt = 0; attempt < kDampingAttempts; ++attempt, lambda *= kDampingGrowth)
    if (solveEnvelopeCholesky(H, lambda, rhs, &x)) return x;
  return VectorXd::Zero(rhs.size());
}

/// Yaw as the heading of one body axis, atan2(y, x) of R·a: it satisfies
/// yaw(Rz(ψ)·R) = yaw(R) + ψ exactly. The axis is the body axis of the
/// anchor state that is the most horizontal, so the heading is well defined at
/// any attitude (a body pointing straight up has a horizontal y axis).
Vec3 mostHorizontalAxis(const SO3& R) {
  const Mat3 M = R.matrix();
  int best = 0;
  for (int k = 1; k < 3; ++k)
    if (std::abs(M(2, k)) < std::abs(M(2, best))) best = k;
  return Vec3::Unit(best);
}

double heading(const SO3& R, const Vec3& body_axis) {
  const Vec3 d = R * body_axis;
  return std::atan2(d.y(), d.x());
}

/// Re-anchoring (METHOD.md §5): rotate about z and shift all states so that
/// the oldest keeps its yaw (its whole attitude with Gauge::kPose) and position.
void reanchor(const NavState& oldest_before, Window* w) {
  const Vec3 axis = mostHorizontalAxis(oldest_before.R_w_b);
  const SO3& R_now = w->states.front().x.R_w_b;
  const SO3 Rz = w->gauge == Gauge::kPose ? oldest_before.R_w_b * R_now.inverse()
                                          : SO3::exp(Vec3(0, 0, heading(oldest_before.R_w_b, axis) - heading(R_now, axis)));
  const Vec3 p_new = w->states.front().x.p_w;
  for (WindowState& st : w->states) {
    st.x.R_w_b = Rz * st.x.R_w_b;
    st.x.p_w = Rz * (st.x.p_w - p_new) + oldest_before.p_w;
    st.x.v_w = Rz * st.x.v_w;
  }
}

/// State k first, then every state that shares an inertial link or a visual
/// link `use_visual` takes with it, then (`with_prior`) those of the old prior.
template <class UseVisual>
std::vector<std::size_t> statesInvolvedWith(const Window& w, std::size_t k, bool with_prior, UseVisual use_visual) {
  std::vector<std::size_t> involved = {k};
  const auto addState = [&](std::size_t i) {
    if (std::find(involved.begin(), involved.end(), i) == involved.end()) involved.push_back(i);
  };
  for (const auto& l : w.inertial)
    if (l.i == k || l.j == k) addState(l.i == k ? l.j : l.i);
  for (const auto& l : w.visual)
    if ((l.r == k || l.n == k) && use_visual(l)) addState(l.r == k ? l.n : l.r);
  if (with_prior)
    for (std::size_t i : w.prior.states) addState(i);
  return involved;
}

}  // namespace

/// Blocks in the window's normal equations: the states, then the calibration's.
std::size_t windowBlocks(const Window& w) { return w.states.size() + (w.calibration ? 1 : 0); }

double windowCost(const Window& w, const EstimatorOptions& o) {
  Normal n(windowBlocks(w), true);
  linearize(w, o, identitySlots(w.states.size()), static_cast<long>(w.states.size()), Priors::kBoth,
            [](const InertialLink&) { return true; }, [](const VisualLink&) { return true; }, &n);
  return n.cost;
}

SolveSummary solve(Window* w, const EstimatorOptions& o) {
  SolveSummary s;
  const std::size_t N = w->states.size();
  if (N == 0) return s;
  const auto slots = identitySlots(N);
  Normal n(windowBlocks(*w));
  std::vector<StructureGroup> groups;
  for (int it = 0; it < o.max_iterations; ++it) {
    if (it > 0) n.reset();  // constructed zero
    groups.clear();
    linearize(*w, o, slots, static_cast<long>(N), Priors::kBoth, [](const InertialLink&) { return true; },
              [](const VisualLink&) { return true; }, &n, &groups);
    if (it == 0) s.initial_cost = n.cost;
    double damping = o.damping;
    if (w->gauge != Gauge::kNone && o.gauge_prior) {
      // Zero residual, so only H changes: the step leaves the gauge directions
      // alone. Its stiffness is relative to the system's, and the damping is
      // scaled back so that it stays what it was without the prior.
      const double stiffness = kGaugeStiffness * std::max(1.0, n.H.diagonal().cwiseAbs().maxCoeff());
      n.H.block<3, 3>(imu::kP, imu::kP) += Mat3::Identity() * stiffness;
      const Vec3 up = w->states.front().x.R_w_b.inverse() * Vec3::UnitZ();  // world yaw in the body's δθ
      n.H.block<3, 3>(imu::kR, imu::kR) += (w->gauge == Gauge::kPose ? Mat3::Identity() : Mat3(up * up.transpose())) * stiffness;
      damping *= 1.0 / kGaugeStiffness;
    }
    const VectorXd step = perturbedCholeskySolve(n.H, -n.g, damping);
    if (!step.allFinite()) {
      s.stopped = true;
      break;
    }
    const NavState oldest = w->states.front().x;
    for (std::size_t k = 0; k < N; ++k) w->states[k].x = boxplus(w->states[k].x, step.segment<15>(15 * static_cast<long>(k)));
    if (w->calibration) w->calibration = boxplus(*w->calibration, step.tail<15>());
    for (const StructureGroup& g : groups) {
      VectorXd dxi(6 * static_cast<long>(g.frames.size()));
      for (std::size_t a = 0; a < g.frames.size(); ++a)
        dxi.segment<6>(6 * static_cast<long>(a)) = g.A[a] * step.segment<6>(15 * static_cast<long>(g.reference)) +
                                                   g.B[a] * step.segment<6>(15 * static_cast<long>(g.frames[a]));
      updateInverseDepths(g.system, dxi, &w->states[g.reference].points);
    }
    if (w->gauge != Gauge::kNone && !o.gauge_prior) reanchor(oldest, w);
    ++s.iterations;
    if (step.norm() < kNegligibleStep) {
      s.stopped = true;
      break;
    }
  }
  s.final_cost = windowCost(*w, o);
  return s;
}

SolveSummary solveNewest(Window* w, const EstimatorOptions& o) {
  SolveSummary s;
  const std::size_t N = w->states.size();
  if (N < 2) return s;  // a lone state is the gauge's
  const std::size_t k = N - 1;
  // Its links' other states; the prior's too when it holds the newest state
  // (after the second-newest was marginalised), with the calibration last.
  const auto touches = [k](std::size_t a, std::size_t b) { return a == k || b == k; };
  const bool in_prior = std::find(w->prior.states.begin(), w->prior.states.end(), k) != w->prior.states.end();
  const std::vector<std::size_t> involved = statesInvolvedWith(*w, k, in_prior, [](const VisualLink&) { return true; });
  std::map<std::size_t, long> slot;
  for (std::size_t a = 0; a < involved.size(); ++a) slot[involved[a]] = static_cast<long>(a);
  const auto blocks = slot.size() + (w->calibration ? 1 : 0);
  const auto linearizeNewest = [&](Normal* n) {
    linearize(*w, o, slot, static_cast<long>(slot.size()), in_prior ? Priors::kMarginal : Priors::kNone,
              [&](const InertialLink& l) { return touches(l.i, l.j); }, [&](const VisualLink& l) { return touches(l.r, l.n); },
              n);
  };
  Normal n(blocks);
  for (int it = 0; it < o.max_iterations; ++it) {
    if (it > 0) n.reset();  // constructed zero
    linearizeNewest(&n);
    if (it == 0) s.initial_cost = n.cost;
    // Every other block held: the newest state's rows and columns alone.
    const Vec15 step = perturbedCholeskySolve(n.H.topLeftCorner<15, 15>(), -n.g.head<15>(), o.damping);
    if (!step.allFinite()) {
      s.stopped = true;
      break;
    }
    w->states[k].x = boxplus(w->states[k].x, step);
    ++s.iterations;
    if (step.norm() < kNegligibleStep) {
      s.stopped = true;
      break;
    }
  }
  Normal cost(blocks, true);  // of the same terms: the whole window's would cost a pass over all of it
  linearizeNewest(&cost);
  s.final_cost = cost.cost;
  return s;
}

namespace {

/// The prior left by marginalising state k: the Schur complement of the
/// normal equations of its inertial links, the visual links `folded` takes
/// and the old prior (eqs 20-21), over the states those involve.
template <class Folded>
MarginalPrior schurPrior(const Window& w, std::size_t k, Folded folded, const EstimatorOptions& o) {
  const std::vector<std::size_t> involved = statesInvolvedWith(w, k, true, folded);
  std::map<std::size_t, long> slot;
  for (std::size_t a = 0; a < involved.size(); ++a) slot[involved[a]] = static_cast<long>(a);
  // The calibration block, when the window has one, is last and stays in the prior.
  Normal n(involved.size() + (w.calibration ? 1 : 0));
  linearize(w, o, slot, static_cast<long>(involved.size()), Priors::kMarginal, [&](const InertialLink& l) { return l.i == k || l.j == k; },
            [&](const VisualLink& l) { return (l.r == k || l.n == k) && folded(l); }, &n);
  // Schur complement on the first 15 rows/columns (state k).
  const long m = 15, r = n.H.rows() - m;
  if (r == 0) return MarginalPrior{};  // nothing links state k to another (a tight link dropped, no IMU): nothing to keep
  const MatrixXd Hmm = n.H.topLeftCorner(m, m), Hrm = n.H.bottomLeftCorner(r, m), Hrr = n.H.bottomRightCorner(r, r);
  const Eigen::LDLT<MatrixXd> Hmm_ldlt(Hmm + MatrixXd::Identity(m, m) * kMarginalRegulariser);
  MarginalPrior prior;
  prior.H = Hrr - Hrm * Hmm_ldlt.solve(Hrm.transpose());
  prior.H = 0.5 * (prior.H + prior.H.transpose());
  prior.b = n.g.tail(r) - Hrm * Hmm_ldlt.solve(n.g.head(m));
  for (std::size_t a = 1; a < involved.size(); ++a) {
    prior.states.push_back(involved[a]);
    prior.x0.push_back(w.states[involved[a]].x);
  }
  if (w.calibration) {
    prior.calibration = true;
    prior.c0 = *w.calibration;
  }
  if (o.first_estimate_jacobians) {
    // States already in the old prior keep their first estimate; b is moved
    // there, so that the quadratic keeps its gradient at the current estimate.
    VectorXd d = VectorXd::Zero(r);
    for (std::size_t q = 0; q < w.prior.states.size(); ++q) {
      const auto a = std::find(involved.begin(), involved.end(), w.prior.states[q]) - involved.begin();
      if (a == 0) continue;  // the state leaving
      prior.x0[static_cast<std::size_t>(a - 1)] = w.prior.x0[q];
      d.segment<15>(15 * (a - 1)) = boxminus(w.states[w.prior.states[q]].x, w.prior.x0[q]);
    }
    if (w.prior.calibration) {
      prior.c0 = w.prior.c0;
      d.tail<15>() = boxminus(*w.calibration, w.prior.c0);
    }
    prior.b -= prior.H * d;
  }
  return prior;
}

}  // namespace

void marginalize(Window* w, std::size_t k, const EstimatorOptions& o) {
  // Front marginalisation (any state but the oldest) may drop the links
  // measured in state k: from a reference that stays, they share its error
  // with the links that stay and come, so folding them in as independent
  // would count that error again in the prior.
  // A tight link measured in state k is dropped whatever the option: its
  // points stay, with the links that stay (DSO drops such residuals too).
  const bool drop_measured = o.front_marginalization_drops_links && k > 0;
  const auto folded = [k, drop_measured, w](const VisualLink& l) {
    if (l.n == k && l.r != k && isTight(*w, l)) return false;
    return !(drop_measured && l.n == k);
  };
  MarginalPrior prior = schurPrior(*w, k, folded, o);
  // Remove state k and every link that touched it; renumber.
  const auto renumber = [k](std::size_t i) { return i > k ? i - 1 : i; };
  std::vector<InertialLink> inertial;
  for (auto& l : w->inertial)
    if (l.i != k && l.j != k) {
      const std::size_t i = renumber(l.i), j = renumber(l.j);
      inertial.push_back(std::move(l));
      inertial.back().i = i;
      inertial.back().j = j;
    }
  std::vector<VisualLink> visual;
  for (auto& l : w->visual)
    if (l.r != k && l.n != k) visual.push_back({renumber(l.r), renumber(l.n), l.link, std::move(l.image)});
  for (auto& i : prior.states) i = renumber(i);
  w->inertial = std::move(inertial);
  w->visual = std::move(visual);
  w->prior = std::move(prior);
  w->states.erase(w->states.begin() + static_cast<long>(k));
}

}  // namespace edgevio::estimator
