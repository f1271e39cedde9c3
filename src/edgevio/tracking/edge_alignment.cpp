#include "edgevio/tracking/edge_alignment.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>

namespace edgevio::tracking {

using geometry::hat;
using geometry::SE3;

namespace {

// A point this close to the camera plane (or behind it) does not project.
constexpr double kMinDepthM = 1e-6;
// A mean distance this much lower than the best so far counts as progress:
// far below the sub-pixel spread of edge positions (~0.05 px), far above rounding.
constexpr double kMinProgressPx = 1e-4;
// The covariance of a fit that leaves the pose free along some direction:
// 1e6 m² (rad²) fails the self check's σ test and weighs nothing in a window.
constexpr double kUnconstrainedVariance = 1e6;

/// T as a rotation matrix and translation, with the level's intrinsics:
/// converted once per pass over the points, not once per point.
struct LevelProjection {
  LevelProjection(const SE3& T, const vision::LevelCamera& c)
      : R(T.rotationMatrix()), t(T.translation()), fx(c.fx), fy(c.fy), cx(c.cx), cy(c.cy) {}
  Mat3 R;
  Vec3 t;
  double fx, fy, cx, cy;
};

/// A point T·P projected: its pixel and, with the Jacobian, the rows a0, a1
/// of ∂uv/∂δp = ∂π/∂P'·R.
struct Projected {
  Vec3 P;
  double u = 0, v = 0;
  Vec3 a0, a1;

  /// ∂(g·uv)/∂ξ for a direction g in the image. T·exp(ξ)·P ≈ T·(P + δp +
  /// δθ × P), so ∂P'/∂ξ = R·[I | −hat(P)] and ∂uv/∂ξ = [A | −A·hat(P)] with
  /// A = (a0; a1), whose rows of −A·hat(P) are (P × a0)ᵀ and (P × a1)ᵀ.
  Jacobian16 directional(double g0, double g1) const {
    Jacobian16 J;
    J << g0 * a0.transpose() + g1 * a1.transpose(), g0 * P.cross(a0).transpose() + g1 * P.cross(a1).transpose();
    return J;
  }

  /// The reference edge's normal in the current image: its tangent, one
  /// keyframe pixel long at P's depth, through ∂uv/∂P (see mapEdgeNormal).
  Vec2 mappedNormal(const Vec2& n_ref, double fx, double fy) const {
    const double dx = -P.z() * n_ref.y() / fx, dy = P.z() * n_ref.x() / fy;
    const double tx = a0.x() * dx + a0.y() * dy, ty = a1.x() * dx + a1.y() * dy;
    const double len = std::sqrt(tx * tx + ty * ty);
    return len > 1e-12 ? Vec2(ty / len, -tx / len) : n_ref;
  }
};

bool project(const Vec3& P, const LevelProjection& T, bool with_jacobian, Projected* out) {
  const Vec3 Pc = T.R * P + T.t;
  if (Pc.z() <= kMinDepthM) return false;
  const double iz = 1.0 / Pc.z();
  const double x = Pc.x() * iz, y = Pc.y() * iz;
  out->P = P;
  out->u = T.fx * x + T.cx;
  out->v = T.fy * y + T.cy;
  if (with_jacobian) {
    out->a0 = T.fx * iz * (T.R.row(0) - x * T.R.row(2)).transpose();
    out->a1 = T.fy * iz * (T.R.row(1) - y * T.R.row(2)).transpose();
  }
  return true;
}

/// Projects P; false when it lands behind the camera or outside the border.
bool projectInside(const Vec3& P, const LevelProjection& T, int width, int height, int border, bool with_jacobian,
                   Projected* p) {
  return project(P, T, with_jacobian, p) && p->u >= border && p->v >= border && p->u <= width - 1 - border &&
         p->v <= height - 1 - border;
}

/// What a projected point reads from the level's distance transform: V and,
/// for the point-to-line residual, the nearest edge line (point e, normal
/// n), else ∇V (in n).
struct Sample {
  float value = 0;
  Vec2 e = Vec2::Zero(), n = Vec2::Zero();
};

Sample sample(const Projected& p, const vision::DistanceTransform& dt, bool point_to_line) {
  Sample s;
  if (point_to_line) {
    s.value = dt.value(p.u, p.v);
    dt.nearestLine(p.u, p.v, &s.e, &s.n);
  } else {
    float gu, gv;
    dt.valueAndGradient(p.u, p.v, &s.value, &gu, &gv);
    s.n = Vec2(gu, gv);
  }
  return s;
}

/// One reference point's residual on a level (see edgeResidual).
struct PointResidual {
  double u = 0, v = 0;    ///< its pixel
  double r = 0;           ///< υ
  double distance = 0;    ///< V(u), whichever residual υ is
  double normal_cos = 1;  ///< mapped reference normal · nearest edge normal (1: not checked)
  Jacobian16 J;           ///< ∂υ/∂ξ
};

/// The residual of a projected point from its sample. `n_ref`: the point's
/// normal in the keyframe, checked against the nearest edge's (point-to-line
/// only; null: not checked).
PointResidual pointResidual(const Projected& p, const Sample& smp, const LevelProjection& T, bool with_jacobian,
                            bool point_to_line, const Eigen::Vector2f* n_ref) {
  PointResidual out;
  out.u = p.u;
  out.v = p.v;
  out.distance = smp.value;
  const Vec2& n = smp.n;
  if (point_to_line) {
    out.r = (Vec2(p.u, p.v) - smp.e).dot(n);
    if (n_ref) out.normal_cos = p.mappedNormal(n_ref->cast<double>(), T.fx, T.fy).dot(n);
  } else {
    out.r = out.distance;
  }
  if (with_jacobian) out.J = p.directional(n.x(), n.y());
  return out;
}

}  // namespace

bool projectWithJacobian(const Vec3& P, const SE3& T, const vision::LevelCamera& c, Vec2* uv, Jacobian26* J) {
  Projected p;
  if (!project(P, LevelProjection(T, c), J != nullptr, &p)) return false;
  *uv = Vec2(p.u, p.v);
  if (J) {
    J->row(0) << p.a0.transpose(), P.cross(p.a0).transpose();
    J->row(1) << p.a1.transpose(), P.cross(p.a1).transpose();
  }
  return true;
}

Vec2 mapEdgeNormal(const Vec3& P, const Vec2& n_ref, const SE3& T, const vision::LevelCamera& c) {
  Projected p;
  const LevelProjection Tc(T, c);
  if (!project(P, Tc, true, &p)) return n_ref;
  return p.mappedNormal(n_ref, Tc.fx, Tc.fy);
}

bool edgeResidual(const Vec3& P, const SE3& T, const vision::LevelCamera& c, const vision::DistanceTransform& dt,
                  int border, double* r, Jacobian16* J, bool point_to_line, double* distance, const Eigen::Vector2f* n_ref,
                  double* normal_cos) {
  const LevelProjection Tc(T, c);
  Projected p;
  if (!projectInside(P, Tc, c.width, c.height, border, J != nullptr, &p)) return false;
  const bool p2l = point_to_line && dt.hasLines();
  const PointResidual res = pointResidual(p, sample(p, dt, p2l), Tc, J != nullptr, p2l, n_ref);
  *r = res.r;
  if (J) *J = res.J;
  if (distance) *distance = res.distance;
  if (normal_cos) *normal_cos = res.normal_cos;
  return true;
}

namespace {

struct LevelStats {
  Mat6 H = Mat6::Zero();
  Vec6 g = Vec6::Zero();
  double sum_r = 0.0;
  int visible = 0;
  int considered = 0;  ///< points evaluated (all, or the strided subset)
};

/// Calls f(residual, w, other_edge) for each reference point (or an even
/// stride of them, o.max_points) that lands inside the level's border: its
/// pixel, residual, Jacobian and distance V, and robust weight w.
/// `normals`: the points' edge normals (null, or of another size: none).
/// Returns the points considered.
template <class F>
int forEachWeightedPoint(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector2f>* normals,
                         const SE3& T, const vision::EdgeLevel& level, const AlignmentOptions& o, bool finest, F&& f) {
  // An even stride keeps the points spread over the image (and deterministic).
  const std::size_t stride =
      o.max_points > 0 && points.size() > static_cast<std::size_t>(o.max_points) ? (points.size() + static_cast<std::size_t>(o.max_points) - 1) / static_cast<std::size_t>(o.max_points) : 1;
  const bool laplacian = o.weight == RobustWeight::kLaplacian;
  const LevelProjection Tc(T, level.camera);
  // The distance field's consistent pull towards edges gives the wide basin
  // on coarse levels; the line residual refines on the finest one.
  const bool p2l = o.residual == Residual::kPointToLine && finest && level.dt.hasLines();
  const bool check_normals = p2l && o.max_normal_angle_deg > 0 && normals && normals->size() == points.size();
  const double min_cos = std::cos(o.max_normal_angle_deg * kDegToRad);
  const int width = level.camera.width, height = level.camera.height;
  // In chunks, three passes: projection, then the chunk's reads of the
  // distance transform (independent loads, their cache misses in flight
  // together; one point at a time the arithmetic waited on each), then the
  // residuals. The same arithmetic per point as one at a time.
  constexpr std::size_t kChunk = 64;
  std::array<Projected, kChunk> projected;
  std::array<Sample, kChunk> samples;
  std::array<std::size_t, kChunk> index;
  int considered = 0;
  std::size_t idx = 0;
  while (idx < points.size()) {
    std::size_t inside = 0;
    for (std::size_t c = 0; c < kChunk && idx < points.size(); ++c, idx += stride) {
      ++considered;
      if (projectInside(points[idx].cast<double>(), Tc, width, height, o.border_px, true, &projected[inside]))
        index[inside++] = idx;
    }
    for (std::size_t c = 0; c < inside; ++c) samples[c] = sample(projected[c], level.dt, p2l);
    for (std::size_t c = 0; c < inside; ++c) {
      const PointResidual res =
          pointResidual(projected[c], samples[c], Tc, true, p2l, check_normals ? &(*normals)[index[c]] : nullptr);
      // Weights from the distance V: the robust kernel judges how far the
      // point is from any edge, whichever residual is minimised. A nearest
      // edge whose normal (with its sign) points elsewhere than the reference
      // edge's is another edge (the other side of a thin line, a crossing
      // edge): weight 0.
      const double d = res.distance;
      const bool other_edge = res.normal_cos < min_cos;
      const double w = other_edge ? 0.0 : laplacian ? std::exp(-d) : 1.0 / (1.0 + d * d / o.cauchy_c2);
      f(res, w, other_edge);
    }
  }
  return considered;
}

LevelStats accumulate(const std::vector<Eigen::Vector3f>& points, const std::vector<Eigen::Vector2f>* normals, const SE3& T,
                      const vision::EdgeLevel& level, const AlignmentOptions& o, bool finest) {
  LevelStats s;
  // Upper triangle of Σ w·JᵀJ, row by row (21 entries), and Σ w·r·Jᵀ.
  double h[21] = {};
  s.considered = forEachWeightedPoint(points, normals, T, level, o, finest, [&](const PointResidual& p, double w, bool) {
    int k = 0;
    for (int i = 0; i < 6; ++i) {
      const double wji = w * p.J[i];
      for (int j = i; j < 6; ++j) h[k++] += wji * p.J[j];
    }
    s.g += w * p.r * p.J.transpose();
    s.sum_r += p.distance;
    ++s.visible;
  });
  int k = 0;
  for (int i = 0; i < 6; ++i)
    for (int j = i; j < 6; ++j) s.H(i, j) = s.H(j, i) = h[k++];
  return s;
}

/// One level of the pyramid as an alignment sees it.
struct LevelInput {
  const std::vector<Eigen::Vector3f>& points;
  const std::vector<Eigen::Vector2f>* normals;
  const vision::EdgeLevel& level;
  int l;
};

/// A pose and the sums of its points at one level.
struct LevelFit {
  SE3 T;
  LevelStats stats;
};

/// Gauss-Newton on one level from T (eqs 9-11), with the rotation prior;
/// returns the best iterate by mean distance. Each pose is evaluated once:
/// `s` always holds the sums at the current T.
LevelFit alignLevel(const LevelInput& in, SE3 T, const AlignmentOptions& o, const RotationPrior* prior, int* iterations) {
  const auto evaluate = [&](const SE3& pose) { return accumulate(in.points, in.normals, pose, in.level, o, in.l == 0); };
  LevelStats s = evaluate(T);
  LevelFit best{T, s};
  double best_mean = std::numeric_limits<double>::infinity();
  int stalled = 0;
  for (int it = 0; it < o.max_iterations_per_level; ++it) {
    if (s.visible < o.min_points) break;
    const double mean = s.sum_r / s.visible;
    // Near the optimum points switch between neighbouring edges, so steps
    // need not shrink; progress is judged on the mean distance instead.
    if (mean < best_mean - kMinProgressPx) {
      best_mean = mean;
      best = {T, s};
      stalled = 0;
    } else if (++stalled >= o.max_stalled_iterations) {
      break;
    }
    ++*iterations;
    Mat6 H = s.H;
    Vec6 g = s.g;
    if (prior && prior->sigma_rad > 0) {
      // r = Log(R_nrᵀ R), ∂r/∂δθ ≈ I for the right perturbation R·Exp(δθ).
      const double lambda = std::ldexp(1.0, -2 * in.l) / (prior->sigma_rad * prior->sigma_rad);
      H.bottomRightCorner<3, 3>() += lambda * Mat3::Identity();
      g.tail<3>() += lambda * (prior->R_nr.inverse() * T.so3()).log();
    }
    const Eigen::LDLT<Mat6> ldlt(H);
    if (ldlt.info() != Eigen::Success) break;
    const Vec6 xi = ldlt.solve(-g);
    if (!xi.allFinite()) break;
    T = T * SE3::exp(xi);
    s = evaluate(T);
    if (xi.norm() < o.min_step) break;
  }
  // The last step counts too: it may be the best iterate.
  if (s.visible < o.min_points || s.sum_r / s.visible > best_mean) return best;
  return {T, s};
}

/// The self check and the covariance (paper §5.3, §6.3) of T at level `finest`.
/// `s`: the sums of the points at T on that level.
void evaluateFit(int finest, const LevelStats& s, const AlignmentOptions& o, AlignmentResult* res) {
  res->points_used = s.visible;
  res->visible_ratio = s.considered == 0 ? 0.0 : static_cast<double>(s.visible) / static_cast<double>(s.considered);
  res->mean_distance_px = s.visible > 0 ? s.sum_r / s.visible : std::numeric_limits<double>::infinity();
  const Eigen::LDLT<Mat6> ldlt(s.H);
  // A singular H leaves the pose free along some direction (a blank or
  // one-edge view): such a result cannot pass, however close to the edges.
  const bool constrained = s.visible >= o.min_points && ldlt.info() == Eigen::Success && ldlt.isPositive();
  res->covariance = constrained ? Mat6(ldlt.solve(Mat6::Identity())) : Mat6(Mat6::Identity() * kUnconstrainedVariance);
  // σ along the weakest direction: points that collapsed onto one spot of an
  // edge lie close to it (small mean distance) yet fix nothing but a ray.
  res->translation_sigma_m =
      res->covariance.allFinite()
          ? std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Mat3>(res->covariance.topLeftCorner<3, 3>(), Eigen::EigenvaluesOnly)
                                        .eigenvalues()
                                        .maxCoeff()))
          : std::numeric_limits<double>::infinity();
  // On a coarser level one residual pixel is 2^finest level-0 pixels.
  res->self_check_passed = constrained && res->covariance.allFinite() &&
                           res->mean_distance_px <= std::ldexp(o.self_check_max_mean_distance_px, -finest) &&
                           res->visible_ratio >= o.self_check_min_visible_ratio &&
                           res->translation_sigma_m <= std::ldexp(o.self_check_max_translation_sigma_m, finest);
}

}  // namespace

AlignmentResult alignEdges(const vision::KeyframeDepth& reference, const vision::EdgePyramid& cur,
                           const SE3& T_init, const AlignmentOptions& o, int coarsest, int finest,
                           const RotationPrior* prior) {
  const auto t0 = std::chrono::steady_clock::now();
  AlignmentResult res;
  const auto& ref = reference.points;
  const auto input = [&](int l) {
    const auto k = static_cast<std::size_t>(l);
    return LevelInput{ref[k], k < reference.normals.size() ? &reference.normals[k] : nullptr, cur.levels[k], l};
  };
  LevelFit fit{T_init, {}};
  int fit_level = -1;  // the level fit.stats belongs to
  int levels = static_cast<int>(std::min(ref.size(), cur.levels.size()));
  if (coarsest >= 0) levels = std::min(levels, coarsest + 1);
  finest = std::clamp(finest, 0, std::max(0, levels - 1));
  for (int l = levels - 1; l >= finest; --l) {
    if (static_cast<int>(ref[static_cast<std::size_t>(l)].size()) < o.min_points) continue;
    fit = alignLevel(input(l), fit.T, o, prior, &res.iterations);
    fit_level = l;
  }
  if (static_cast<int>(ref.size()) > finest && static_cast<int>(cur.levels.size()) > finest) {
    if (fit_level != finest) {
      const LevelInput in = input(finest);
      fit.stats = accumulate(in.points, in.normals, fit.T, in.level, o, finest == 0);
    }
    evaluateFit(finest, fit.stats, o, &res);
  }
  res.T_nr = fit.T;
  res.ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  return res;
}

std::vector<ReprojectedPoint> reprojectReferencePoints(const vision::KeyframeDepth& reference,
                                                       const vision::EdgePyramid& current, const SE3& T_nr,
                                                       const AlignmentOptions& o) {
  std::vector<ReprojectedPoint> out;
  if (reference.points.empty() || current.levels.empty()) return out;
  const std::vector<Eigen::Vector2f>* normals = reference.normals.empty() ? nullptr : &reference.normals[0];
  forEachWeightedPoint(reference.points[0], normals, T_nr, current.levels[0], o, true,
                       [&](const PointResidual& p, double w, bool other_edge) {
                         const PointFit fit = other_edge ? PointFit::kOtherEdge : w >= 0.5 ? PointFit::kInlier : PointFit::kOutlier;
                         out.push_back({static_cast<float>(p.u), static_cast<float>(p.v), fit});
                       });
  return out;
}

}  // namespace edgevio::tracking
