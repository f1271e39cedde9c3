#include "edgevio/eval/eval_options.h"

namespace edgevio::eval {

std::string EvalOptions::validate() const {
  if (!(association_tolerance_s > 0.0)) return "association_tolerance_s: must be > 0";
  if (alignment != "se3" && alignment != "sim3" && alignment != "posyaw" && alignment != "none")
    return "alignment: must be one of se3, sim3, posyaw, none (got '" + alignment + "')";
  for (double d : rpe_deltas_m)
    if (!(d > 0.0)) return "rpe_deltas_m: every delta must be > 0";
  for (double p : are_segments_percent)
    if (!(p > 0.0 && p <= 100.0)) return "are_segments_percent: every value must be in (0, 100]";
  for (double m : are_segments_m)
    if (!(m > 0.0)) return "are_segments_m: every length must be > 0";
  return {};
}

}  // namespace edgevio::eval
