#pragma once
#include <vector>

#include "edgevio/common/options.h"
#include "edgevio/eval/alignment.h"

namespace edgevio::eval {

/// Trajectory evaluation (config section `eval`; METHOD.md §8).
struct EvalOptions {
  double association_tolerance_s;
  AlignmentKind alignment;
  std::vector<double> rpe_deltas_m, are_segments_percent, are_segments_m;

  EDGEVIO_OPTIONS(EvalOptions)
};

// EvalOptions's keys, defaults, units, meanings and valid values: its table in eval_options.cpp.

}  // namespace edgevio::eval
