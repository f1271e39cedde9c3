#pragma once
#include <string>
#include <vector>

namespace edgevio::eval {

/// Options of trajectory evaluation (config section `eval`; METHOD.md §8).
struct EvalOptions {
  /// Largest |t_est − t_gt| for two poses to be associated. [s]
  double association_tolerance_s = 0.01;
  /// Alignment before ATE: se3 (Umeyama, no scale), sim3, posyaw (4-DoF) or none.
  std::string alignment = "se3";
  /// Travelled-distance deltas of the RPE (evo convention). [m]
  std::vector<double> rpe_deltas_m = {1.0, 5.0};
  /// ARE segment lengths as percentages of the trajectory length (used when are_segments_m is empty). [%]
  std::vector<double> are_segments_percent = {10.0, 20.0, 30.0, 40.0, 50.0};
  /// ARE segment lengths in metres; when non-empty they replace the percentages. [m]
  std::vector<double> are_segments_m = {};

  template <class Visitor>
  void visit(Visitor& v) {
    v("association_tolerance_s", association_tolerance_s, "s", "largest |t_est - t_gt| for two poses to be matched");
    v("alignment", alignment, "-", "alignment before ATE: se3 | sim3 | posyaw | none");
    v("rpe_deltas_m", rpe_deltas_m, "m", "travelled-distance deltas of the RPE (evo pairing)");
    v("are_segments_percent", are_segments_percent, "%", "ARE segment lengths, percent of trajectory length");
    v("are_segments_m", are_segments_m, "m", "ARE segment lengths in metres; non-empty replaces the percentages");
  }
  std::string validate() const;
};

}  // namespace edgevio::eval
