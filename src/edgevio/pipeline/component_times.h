#pragma once
// Per-component processing times of a run, read back from its frames.csv:
// the layout of the paper's Table 1 (ms per frame; block matching, back links
// and loop closure per keyframe), for `edgevio bench` and bench/pipeline_bench.
// The components are the columns of frameColumns() that name one.
#include <string>
#include <vector>

namespace edgevio::pipeline {

struct ComponentTime {
  std::string component;  ///< e.g. "edge alignment"
  std::string per;        ///< frame | keyframe
  double mean_ms = 0, median_ms = 0, p90_ms = 0;
  std::size_t count = 0;  ///< frames (or keyframes) that ran the component
};

/// Every component of frameColumns(), in column order; one with no sample
/// (e.g. the estimator in edge-only) has count 0. Throws InputError when the
/// file cannot be read.
std::vector<ComponentTime> readComponentTimes(const std::string& frames_csv);

}  // namespace edgevio::pipeline
