#include "edgevio/eval/svg_plot.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/time.h"

namespace edgevio::eval {

namespace {

constexpr const char* kGtColour = "#222222";
constexpr const char* kEstColour = "#d9480f";

std::string fmt(double v) { return formatText("%.2f", v); }


/// A tick step of 1, 2 or 5 times a power of ten giving about `target` ticks.
double niceStep(double range, int target) {
  if (!(range > 0.0)) return 1.0;
  const double raw = range / target;
  const double p = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0, 10.0})
    if (m * p >= raw) return m * p;
  return 10.0 * p;
}

std::string tickLabel(double v, double step) {
  const int decimals = step >= 1.0 ? 0 : static_cast<int>(std::ceil(-std::log10(step) - 1e-9));
  return formatText("%.*f", decimals, std::abs(v) < 1e-12 ? 0.0 : v);
}

/// A plotting panel mapping data coordinates to a pixel rectangle.
struct Panel {
  double x0, y0, w, h;              // pixel rectangle
  double xmin, xmax, ymin, ymax;    // data range
  double px(double x) const { return x0 + (x - xmin) / (xmax - xmin) * w; }
  double py(double y) const { return y0 + h - (y - ymin) / (ymax - ymin) * h; }
};

void axes(std::ostringstream& o, const Panel& p, const std::string& xlabel, const std::string& ylabel) {
  o << "<rect x='" << fmt(p.x0) << "' y='" << fmt(p.y0) << "' width='" << fmt(p.w) << "' height='" << fmt(p.h)
    << "' fill='white' stroke='#888'/>\n";
  const double sx = niceStep(p.xmax - p.xmin, 6), sy = niceStep(p.ymax - p.ymin, 6);
  for (double x = std::ceil(p.xmin / sx) * sx; x <= p.xmax + 1e-9 * sx; x += sx) {
    o << "<line x1='" << fmt(p.px(x)) << "' y1='" << fmt(p.y0) << "' x2='" << fmt(p.px(x)) << "' y2='"
      << fmt(p.y0 + p.h) << "' stroke='#e4e4e4'/>\n";
    o << "<text x='" << fmt(p.px(x)) << "' y='" << fmt(p.y0 + p.h + 16) << "' text-anchor='middle'>"
      << tickLabel(x, sx) << "</text>\n";
  }
  for (double y = std::ceil(p.ymin / sy) * sy; y <= p.ymax + 1e-9 * sy; y += sy) {
    o << "<line x1='" << fmt(p.x0) << "' y1='" << fmt(p.py(y)) << "' x2='" << fmt(p.x0 + p.w) << "' y2='"
      << fmt(p.py(y)) << "' stroke='#e4e4e4'/>\n";
    o << "<text x='" << fmt(p.x0 - 6) << "' y='" << fmt(p.py(y) + 4) << "' text-anchor='end'>" << tickLabel(y, sy)
      << "</text>\n";
  }
  o << "<text x='" << fmt(p.x0 + p.w / 2) << "' y='" << fmt(p.y0 + p.h + 36) << "' text-anchor='middle'>"
    << escapeXml(xlabel) << "</text>\n";
  o << "<text transform='translate(" << fmt(p.x0 - 46) << "," << fmt(p.y0 + p.h / 2)
    << ") rotate(-90)' text-anchor='middle'>" << escapeXml(ylabel) << "</text>\n";
}

void polyline(std::ostringstream& o, const Panel& p, const std::vector<double>& xs, const std::vector<double>& ys,
              const char* colour, double width) {
  o << "<polyline fill='none' stroke='" << colour << "' stroke-width='" << width << "' stroke-linejoin='round' points='";
  // Thin out to at most ~4000 vertices: a plot does not need more, and files stay small.
  const std::size_t step = std::max<std::size_t>(1, xs.size() / 4000);
  for (std::size_t i = 0; i < xs.size(); i += step) o << fmt(p.px(xs[i])) << "," << fmt(p.py(ys[i])) << " ";
  if (!xs.empty()) o << fmt(p.px(xs.back())) << "," << fmt(p.py(ys.back()));
  o << "'/>\n";
}

void legendEntry(std::ostringstream& o, double x, double y, const char* colour, const std::string& label,
                 bool dashed = false) {
  o << "<line x1='" << fmt(x) << "' y1='" << fmt(y) << "' x2='" << fmt(x + 24) << "' y2='" << fmt(y)
    << "' stroke='" << colour << "' stroke-width='2.5'" << (dashed ? " stroke-dasharray='6,4'" : "") << "/>\n";
  o << "<text x='" << fmt(x + 30) << "' y='" << fmt(y + 4) << "'>" << escapeXml(label) << "</text>\n";
}

}  // namespace

std::string escapeXml(const std::string& s) {
  std::string r;
  for (char c : s) {
    if (c == '<') r += "&lt;";
    else if (c == '>') r += "&gt;";
    else if (c == '&') r += "&amp;";
    else if (c == '"') r += "&quot;";
    else r += c;
  }
  return r;
}

std::string svgPlot(const EvalResult& r, const std::string& title) {
  const double W = 1100, H = 590;
  std::ostringstream o;
  o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' viewBox='0 0 " << W << " "
    << H << "' font-family='sans-serif' font-size='12'>\n";
  o << "<rect width='100%' height='100%' fill='#fafafa'/>\n";
  const std::string summary = formatText("%zu matched poses, %s alignment, ATE RMSE %.4f m, length %.1f m", r.matched,
                                         alignmentName(r.alignment).c_str(), r.ate_rmse_m, r.length_m);
  o << "<text x='20' y='26' font-size='16' font-weight='bold'>" << escapeXml(title) << "</text>\n";
  o << "<text x='20' y='46' fill='#444'>" << summary << "</text>\n";

  // Top view with equal axis scales, so shapes are not distorted.
  std::vector<double> gx, gy, ex, ey;
  for (const Vec3& p : r.gt_positions) {
    gx.push_back(p.x());
    gy.push_back(p.y());
  }
  for (const Vec3& p : r.est_positions_aligned) {
    ex.push_back(p.x());
    ey.push_back(p.y());
  }
  double xmin = 0, xmax = 1, ymin = 0, ymax = 1;
  if (!gx.empty()) {
    xmin = std::min(*std::min_element(gx.begin(), gx.end()), *std::min_element(ex.begin(), ex.end()));
    xmax = std::max(*std::max_element(gx.begin(), gx.end()), *std::max_element(ex.begin(), ex.end()));
    ymin = std::min(*std::min_element(gy.begin(), gy.end()), *std::min_element(ey.begin(), ey.end()));
    ymax = std::max(*std::max_element(gy.begin(), gy.end()), *std::max_element(ey.begin(), ey.end()));
  }
  const double pw = 440, ph = 420;
  double span = std::max({xmax - xmin, (ymax - ymin) * pw / ph, 0.1}) * 1.08;
  const double cx = 0.5 * (xmin + xmax), cy = 0.5 * (ymin + ymax);
  Panel top{80, 80, pw, ph, cx - span / 2, cx + span / 2, cy - span * ph / pw / 2, cy + span * ph / pw / 2};
  o << "<text x='" << fmt(top.x0) << "' y='72' font-weight='bold'>Top view</text>\n";
  axes(o, top, "x [m]", "y [m]");
  polyline(o, top, gx, gy, kGtColour, 1.5);
  polyline(o, top, ex, ey, kEstColour, 1.5);
  if (!gx.empty())
    o << "<circle cx='" << fmt(top.px(gx[0])) << "' cy='" << fmt(top.py(gy[0])) << "' r='4' fill='#2b8a3e'/>\n";

  // ATE over time.
  std::vector<double> t;
  for (std::int64_t ns : r.t_ns) t.push_back(toSeconds(ns - r.t_ns.front()));
  const double tmax = t.empty() ? 1.0 : std::max(t.back(), 1e-3);
  const double emax = r.ate_errors_m.empty() ? 1.0 : std::max(*std::max_element(r.ate_errors_m.begin(), r.ate_errors_m.end()) * 1.1, 1e-3);
  Panel err{620, 80, 440, 420, 0.0, tmax, 0.0, emax};
  o << "<text x='" << fmt(err.x0) << "' y='72' font-weight='bold'>Absolute trajectory error</text>\n";
  axes(o, err, "time since first matched pose [s]", "ATE [m]");
  polyline(o, err, t, r.ate_errors_m, kEstColour, 1.2);
  o << "<line x1='" << fmt(err.x0) << "' y1='" << fmt(err.py(r.ate_rmse_m)) << "' x2='" << fmt(err.x0 + err.w)
    << "' y2='" << fmt(err.py(r.ate_rmse_m)) << "' stroke='#1c7ed6' stroke-dasharray='6,4'/>\n";

  legendEntry(o, 100, H - 18, kGtColour, "ground truth");
  legendEntry(o, 240, H - 18, kEstColour, "estimate (aligned)");
  o << "<circle cx='412' cy='" << fmt(H - 18) << "' r='4' fill='#2b8a3e'/><text x='422' y='" << fmt(H - 14)
    << "'>start</text>\n";
  legendEntry(o, 640, H - 18, "#1c7ed6", "ATE RMSE", true);
  o << "</svg>\n";
  return o.str();
}

std::string svgLineChart(const std::string& title, const std::string& xlabel, const std::string& ylabel,
                         const std::vector<PlotSeries>& series, double marker_x) {
  const double W = 760, H = 340;
  double xmin = std::numeric_limits<double>::infinity(), xmax = -xmin, ymin = xmin, ymax = -xmin;
  for (const PlotSeries& s : series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      xmin = std::min(xmin, s.x[i]);
      xmax = std::max(xmax, s.x[i]);
      ymin = std::min(ymin, s.y[i]);
      ymax = std::max(ymax, s.y[i]);
    }
  if (!(xmax > xmin)) {
    xmin = std::isfinite(xmin) ? xmin - 0.5 : 0.0;
    xmax = xmin + 1.0;
  }
  if (!(ymax > ymin)) {
    ymin = std::isfinite(ymin) ? ymin - 0.5 : 0.0;
    ymax = ymin + 1.0;
  }
  const double pad = 0.05 * (ymax - ymin);
  const Panel p{80, 40, W - 110, H - 110, xmin, xmax, ymin - pad, ymax + pad};
  std::ostringstream o;
  o << "<svg xmlns='http://www.w3.org/2000/svg' width='" << W << "' height='" << H << "' viewBox='0 0 " << W << " "
    << H << "' font-family='sans-serif' font-size='12'>\n";
  o << "<rect width='100%' height='100%' fill='#fafafa'/>\n";
  o << "<text x='20' y='24' font-size='14' font-weight='bold'>" << escapeXml(title) << "</text>\n";
  axes(o, p, xlabel, ylabel);
  for (const PlotSeries& s : series) polyline(o, p, s.x, s.y, s.colour.c_str(), 1.5);
  if (std::isfinite(marker_x) && marker_x >= xmin && marker_x <= xmax)
    o << "<line x1='" << fmt(p.px(marker_x)) << "' y1='" << fmt(p.y0) << "' x2='" << fmt(p.px(marker_x)) << "' y2='"
      << fmt(p.y0 + p.h) << "' stroke='#1c7ed6' stroke-dasharray='6,4'/>\n";
  double lx = 100;
  for (const PlotSeries& s : series) {
    legendEntry(o, lx, H - 14, s.colour.c_str(), s.label);
    lx += 60 + 7.0 * static_cast<double>(s.label.size());
  }
  o << "</svg>\n";
  return o.str();
}

void writeSvgPlot(const std::string& path, const EvalResult& r, const std::string& title) {
  std::ofstream f(path);
  if (!f) throw InputError(path, 0, "cannot write the plot (does the folder exist?)");
  f << svgPlot(r, title);
}

}  // namespace edgevio::eval
