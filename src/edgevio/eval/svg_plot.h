#pragma once
// SVG plots written by the program itself (no GUI, no plotting library):
// a top view (x-y) of the aligned estimate over the ground truth, and the ATE
// over time, side by side with axes, units and a legend; and a general line
// chart (the doctor's evidence).
#include <limits>
#include <string>
#include <vector>

#include "edgevio/eval/metrics.h"

namespace edgevio::eval {

/// Writes the plot to `path` (throws InputError when it cannot be written).
void writeSvgPlot(const std::string& path, const EvalResult& r, const std::string& title);

/// The SVG text itself.
std::string svgPlot(const EvalResult& r, const std::string& title);

/// `s` safe as XML or HTML text and attribute values.
std::string escapeXml(const std::string& s);

/// One curve of a line chart.
struct PlotSeries {
  std::string label;
  std::string colour;  ///< any SVG colour, e.g. "#d9480f"
  std::vector<double> x, y;
};
/// Series in one panel with axes spanning all of them, and a legend; an
/// optional dashed vertical marker at `marker_x` (NaN: none).
std::string svgLineChart(const std::string& title, const std::string& xlabel, const std::string& ylabel,
                         const std::vector<PlotSeries>& series, double marker_x = std::numeric_limits<double>::quiet_NaN());

}  // namespace edgevio::eval
