#pragma once
// SVG plots written by the program itself (no GUI, no plotting library):
// a top view (x-y) of the aligned estimate over the ground truth, and the ATE
// over time, side by side with axes, units and a legend.
#include <string>

#include "edgevio/eval/metrics.h"

namespace edgevio::eval {

/// Writes the plot to `path` (throws InputError when it cannot be written).
void writeSvgPlot(const std::string& path, const EvalResult& r, const std::string& title);

/// The SVG text itself.
std::string svgPlot(const EvalResult& r, const std::string& title);

}  // namespace edgevio::eval
