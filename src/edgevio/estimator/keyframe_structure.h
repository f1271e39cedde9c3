#pragma once
// Tight coupling (estimator.coupling: tight; issue 31, point 3): a tracking
// link is no longer the alignment's relative pose with its covariance but
// the edge residuals themselves, of the keyframe's reference points in the
// frame's image, with each point's inverse depth a variable of the window
// held near its stereo measurement. Every link from one keyframe then
// shares that keyframe's depth errors through the same variables, instead
// of each link carrying them as if its own.
//
// For a keyframe r and the frames n_a linked to it, with T_a = T_{n_a r}
// (the links' relative poses, perturbed on the right by twists ξ_a) and the
// points P_i = ray_i/ρ_i:
//   cost = ½ Σ_a Σ_i huber(υ(T_a·P_i))/σ² + ½ Σ_i I_ρ (ρ_i − ρ_i^stereo)²
// υ is the front end's residual (point-to-line near an edge, the distance
// transform beyond; tracking/edge_alignment.h) on level 0 of frame n_a's
// pyramid. Gauss-Newton in (ξ, ρ): the Hessian's ρ block is diagonal, so the
// inverse depths are eliminated point by point (Schur complement), leaving a
// system in the links' twists that the window maps to its states; after the
// step, each ρ_i follows from the twists' steps (back-substitution).
#include <Eigen/Core>

#include <memory>
#include <vector>

#include "edgevio/geometry/se3.h"
#include "edgevio/vision/edge_pyramid.h"
#include "edgevio/vision/keyframe_depth.h"

namespace edgevio::estimator {

/// A keyframe's reference points as variables of the window.
struct KeyframePoints {
  std::vector<Vec3> rays;          ///< in the keyframe's rectified left camera, z = 1: the point is ray/ρ
  /// Each point's edge normal in the keyframe's image (empty: no normal check).
  std::vector<Eigen::Vector2f> normals;
  /// A residual whose nearest edge's normal is farther than this cosine from
  /// the point's mapped normal measures another edge and is left out (the
  /// front end's normal check, alignment.max_normal_angle_deg).
  double min_normal_cos = -1.0;
  std::vector<double> rho;         ///< inverse depth, the estimate [1/m]
  std::vector<double> rho_stereo;  ///< inverse depth from block matching [1/m]
  double rho_information = 0.0;    ///< I_ρ = 1/σ_ρ² of block matching's inverse depth [m²]
  bool empty() const { return rays.empty(); }
};

/// At most `max_points` of the keyframe's level-0 reference points, evenly
/// strided, with their normals and the normal check's angle (0: none). σ_ρ = disparity_sigma_px / (f·b) with f the level-0 focal length
/// [px] (block matching's disparities are level-0 pixels) and b the depth's baseline.
KeyframePoints selectKeyframePoints(const vision::KeyframeDepth& depth, const vision::LevelCamera& level0, int max_points,
                                    double disparity_sigma_px, double max_normal_angle_deg);

/// How an edge residual is weighed: ½ huber(υ)/σ², υ in level-0 pixels
/// (estimator.tight_pixel_sigma_px, tight_huber_px).
struct EdgeWeighting {
  double sigma_px, huber_px;
};

/// One link from the keyframe: its relative pose now, and the frame's pyramid.
struct StructureLink {
  geometry::SE3 T_nr;
  const vision::EdgePyramid* image = nullptr;
};

/// The edge residuals of one keyframe's points in its links' frames, the
/// inverse depths eliminated: ½ξᵀHξ + gᵀξ + cost over the stacked twists ξ
/// (6 per link, (δp, δθ) of T_nr ⊞ ξ), and what back-substitution needs.
struct StructureSystem {
  Eigen::MatrixXd H;  ///< 6k x 6k
  Eigen::VectorXd g;  ///< 6k
  double cost = 0.0;  ///< at the current twists and inverse depths
  struct Point {
    double h_rho = 0.0, g_rho = 0.0;             ///< ∂²/∂ρ² and ∂/∂ρ of the cost
    std::vector<std::pair<int, Vec6>> coupling;  ///< (link, ∂²cost/∂ξ∂ρ) of the links that see it
  };
  std::vector<Point> points;
  int residuals = 0;  ///< point observations inside the links' images
};

/// Linearises the residuals (`cost_only`: the cost alone, H, g and points left empty).
StructureSystem linearizeStructure(const KeyframePoints& kp, const std::vector<StructureLink>& links,
                                   const EdgeWeighting& w, bool cost_only = false);

/// Back-substitution: each ρ_i after the twists' steps dξ (6 per link), kept positive.
void updateInverseDepths(const StructureSystem& s, const Eigen::VectorXd& dxi, KeyframePoints* kp);

}  // namespace edgevio::estimator
