#pragma once
#include <string>

namespace edgevio::loop {

/// Options of local loop closure (config section `loop`; METHOD.md §6).
struct LoopOptions {
  double max_distance_depth_ratio = 0.5;     ///< candidate: camera centres closer than this times the new keyframe's median depth [-]
  double max_view_angle_deg = 30.0;          ///< candidate: optical axes closer than this [deg]
  int skip_recent_keyframes = 1;             ///< the newest keyframes before the new one are no candidates (tracking links them) [-]
  int cross_check_level = 1;                 ///< the cross check aligns from the top of the pyramid down to this level (1: 188x120) [-]
  int max_coarse_attempts = 4;               ///< candidates cross-checked on the coarse levels per keyframe [-]
  int max_full_attempts = 2;                 ///< survivors re-aligned through all levels per keyframe [-]
  double max_ms = 20.0;                      ///< real-time mode: no new attempt starts after this much time per keyframe [ms]
  double coarse_max_mean_distance_px = 1.0;  ///< coarse self check: mean distance at cross_check_level, its pixels [px]
  double coarse_min_visible_ratio = 0.3;     ///< coarse self check: fraction of points in view [-]
  double max_disagreement_m = 0.05;          ///< the two directions' composition: translation off identity [m]
  double max_disagreement_deg = 1.5;         ///< ... rotation off identity [deg]
  double min_visible_ratio = 0.4;            ///< full alignment: fraction of level-0 points in view [-]

  template <class Visitor>
  void visit(Visitor& v) {
    v("max_distance_depth_ratio", max_distance_depth_ratio, "-", "candidate: camera centres closer than this times the new keyframe's median depth");
    v("max_view_angle_deg", max_view_angle_deg, "deg", "candidate: optical axes closer than this");
    v("skip_recent_keyframes", skip_recent_keyframes, "-", "the newest keyframes before the new one are no candidates (tracking links them)");
    v("cross_check_level", cross_check_level, "-", "the cross check aligns from the pyramid top down to this level (1 = 188x120; 2 = 94x60 was too coarse)");
    v("max_coarse_attempts", max_coarse_attempts, "-", "candidates cross-checked on the coarse levels per keyframe");
    v("max_full_attempts", max_full_attempts, "-", "survivors re-aligned through all levels per keyframe");
    v("max_ms", max_ms, "ms", "real-time mode: no new attempt after this much loop-closure time per keyframe (offline: attempts only, for determinism)");
    v("coarse_max_mean_distance_px", coarse_max_mean_distance_px, "px", "coarse self check: mean distance at cross_check_level, in its pixels");
    v("coarse_min_visible_ratio", coarse_min_visible_ratio, "-", "coarse self check: fraction of points in view");
    v("max_disagreement_m", max_disagreement_m, "m", "cross check: composition of both directions, translation off identity");
    v("max_disagreement_deg", max_disagreement_deg, "deg", "cross check: composition of both directions, rotation off identity");
    v("min_visible_ratio", min_visible_ratio, "-", "full alignment self check: fraction of level-0 points in view");
  }
  std::string validate() const;
};

}  // namespace edgevio::loop
