#pragma once
// Edge alignment (METHOD.md §3, paper §5): the pose T_nr that maps reference
// edge points P_i (keyframe camera frame) into the current camera so that
// they land on the current frame's edges:
//   υ_i(T) = V_n(π(T·P_i))                        (eq 5, V = distance transform)
//   f(T) = Σ w_i υ_i²                             (eq 6, robust weights w_i)
// Deviation (AlignmentOptions::residual, default point_to_line): near an edge
// υ_i is replaced by the signed distance to the nearest sub-pixel edge line;
// V's cone tip stalls Gauss-Newton at ~0.5 px (see vision/distance_transform.h).
// Gauss-Newton on SE(3) with right perturbations T ← T·exp(ξ), ξ = (δp, δθ):
//   J_i = ∇V(u)ᵀ · ∂π/∂P' · R·[I | −hat(P_i)],   (JᵀWJ) ξ = −JᵀWυ   (eqs 9-11)
// coarse to fine over the pyramid, keeping the best iterate per level.
// Deviation (AlignmentOptions::max_normal_angle_deg): on the finest level a
// point whose nearest edge has a normal (with the gradient's sign) more than
// 45° from its own edge's normal mapped into the current image
// (mapEdgeNormal) gets weight 0 for that iteration: that edge is another one,
// the far side of a thin line or a crossing edge (the association test of
// oriented nearest-neighbour fields, Zhou et al., Canny-VO, 2018).
// Deviation (IMU modes): a rotation prior from the gyroscope adds
// ½‖Log(R_priorᵀ R)‖²/σ² to f; far scenes leave rotation and lateral
// translation nearly interchangeable, and the gyroscope tells them apart. The
// covariance of the result is (JᵀWJ)⁻¹ at the last finest-level iteration
// (paper §6.3), in the current camera frame's tangent space.
#include <Eigen/Core>

#include <vector>

#include "edgevio/geometry/se3.h"
#include "edgevio/tracking/alignment_options.h"
#include "edgevio/vision/edge_pyramid.h"
#include "edgevio/vision/keyframe_depth.h"

namespace edgevio::tracking {

using Jacobian16 = Eigen::Matrix<double, 1, 6>;
using Jacobian26 = Eigen::Matrix<double, 2, 6>;

/// Pixel of T·P at a level and its Jacobian ∂(u,v)/∂ξ; false when Z ≤ 0.
bool projectWithJacobian(const Vec3& P, const geometry::SE3& T, const vision::LevelCamera& cam, Vec2* uv,
                         Jacobian26* J);

/// υ and ∂υ/∂ξ of one reference point; false when it lands outside the
/// border or behind the camera (the point is dropped for this iteration).
/// With `point_to_line` (and lines in `dt`) υ is the signed distance to the
/// nearest edge line, (u − e)·n, and ∂υ/∂ξ = nᵀ ∂u/∂ξ; else υ = V(u) (eq 5).
/// `distance` (optional) receives V(u) either way, for the self check.
/// With `n_ref` (the point's edge normal in the keyframe; point-to-line
/// only), `normal_cos` receives the cosine of the normal check (1 unchecked).
bool edgeResidual(const Vec3& P, const geometry::SE3& T, const vision::LevelCamera& cam,
                  const vision::DistanceTransform& dt, int border, double* r, Jacobian16* J,
                  bool point_to_line = false, double* distance = nullptr, const Eigen::Vector2f* n_ref = nullptr,
                  double* normal_cos = nullptr);

/// The unit normal, in the current image, of the edge through P whose normal
/// in the keyframe's image is n_ref (the signed grey-level gradient
/// direction): the edge's tangent τ = (−n_y, n_x), one keyframe pixel long
/// at P's depth, maps through ∂uv/∂P to τ', whose normal (τ'_y, −τ'_x)/|τ'|
/// keeps the gradient's sign. n_ref itself when P is behind the camera.
Vec2 mapEdgeNormal(const Vec3& P, const Vec2& n_ref, const geometry::SE3& T, const vision::LevelCamera& cam);

struct AlignmentResult {
  geometry::SE3 T_nr;
  Mat6 covariance = Mat6::Identity();  ///< (JᵀWJ)⁻¹ at level 0 [m², rad²]
  bool self_check_passed = false;
  double mean_distance_px = 0.0;       ///< mean υ of the visible points at the finest level (its pixels)
  double visible_ratio = 0.0;          ///< fraction of the finest level's points inside the image
  int points_used = 0;                 ///< visible points at the finest level
  double translation_sigma_m = 0.0;    ///< √ of the largest eigenvalue of the covariance's translation block [m]
  int iterations = 0;                  ///< over all levels
  double ms = 0.0;
};

/// A prior on the rotation of T_nr from the gyroscope, added to the normal
/// equations as ½‖Log(R_nrᵀ R)‖²/σ² on the scale where one edge residual has
/// a standard deviation of 1 level-0 pixel (so 4^−l times that on level l).
struct RotationPrior {
  geometry::SO3 R_nr;
  double sigma_rad = 0.0;
};

/// Aligns the reference points (per level, keyframe camera frame) to the
/// current pyramid, starting from T_nr_init, from level `coarsest` (−1: the
/// coarsest available) down to level `finest`. The self check and covariance
/// are evaluated at `finest`, the distance threshold scaled to its pixels (2^−finest).
AlignmentResult alignEdges(const vision::KeyframeDepth& reference,
                           const vision::EdgePyramid& current, const geometry::SE3& T_nr_init,
                           const AlignmentOptions& options, int coarsest = -1, int finest = 0,
                           const RotationPrior* rotation_prior = nullptr);

/// How the finest level of an alignment weighs a reference point.
enum class PointFit {
  kInlier,     ///< robust weight ≥ ½: it lies on an edge
  kOutlier,    ///< robust weight < ½: far from any edge
  kOtherEdge,  ///< weight 0: its nearest edge's normal failed the normal check (max_normal_angle_deg)
};

struct ReprojectedPoint {
  float u = 0, v = 0;  ///< level-0 pixel
  PointFit fit = PointFit::kInlier;
};

/// The keyframe's level-0 reference points at T_nr in the current image, as
/// the alignment's finest level weighs them (the same stride of points);
/// points outside the border or behind the camera are left out. What the
/// alignment picture draws.
std::vector<ReprojectedPoint> reprojectReferencePoints(const vision::KeyframeDepth& reference,
                                                       const vision::EdgePyramid& current, const geometry::SE3& T_nr,
                                                       const AlignmentOptions& options);

}  // namespace edgevio::tracking
