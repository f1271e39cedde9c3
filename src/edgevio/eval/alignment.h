#pragma once
// Alignment of an estimated trajectory to ground truth before the ATE
// (METHOD.md §8). Every kind returns a similarity p_gt ≈ s·R·p_est + t fitted
// to the associated positions by least squares:
//  - se3:    Umeyama (1991) with s = 1;
//  - sim3:   Umeyama with scale;
//  - posyaw: rotation about the gravity (z) axis and translation only (4-DoF,
//            the unobservable directions of a VIO);
//  - none:   identity.
#include <string>
#include <vector>

#include "edgevio/common/options.h"
#include "edgevio/geometry/se3.h"

namespace edgevio::eval {

enum class AlignmentKind { kSe3, kSim3, kPosYaw, kNone };
inline constexpr options::Choice<AlignmentKind> kAlignmentChoices[] = {
    {AlignmentKind::kSe3, "se3", "rotation and translation (Umeyama)"},
    {AlignmentKind::kSim3, "sim3", "rotation, translation and scale (Umeyama)"},
    {AlignmentKind::kPosYaw, "posyaw", "translation and rotation about gravity (4-DoF)"},
    {AlignmentKind::kNone, "none", "identity"}};

inline std::string alignmentName(AlignmentKind kind) { return options::nameOf(kAlignmentChoices, kind); }
/// Fewest associated poses each kind needs (3 points fix a rotation, 2 a yaw).
std::size_t minimumPoses(AlignmentKind kind);

struct Similarity {
  double scale = 1.0;
  geometry::SE3 T;  ///< rotation and translation
  Vec3 apply(const Vec3& p) const { return T.so3() * (scale * p) + T.translation(); }
  /// Applies to a pose: rotation composed, position transformed.
  geometry::SE3 apply(const geometry::SE3& pose) const {
    return geometry::SE3(T.so3() * pose.so3(), apply(pose.translation()));
  }
};

/// Fits the alignment mapping `est` positions onto `gt` positions (same length).
Similarity align(const std::vector<Vec3>& est, const std::vector<Vec3>& gt, AlignmentKind kind);

}  // namespace edgevio::eval
