#include "edgevio/pipeline/component_times.h"

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "edgevio/common/error.h"

namespace edgevio::pipeline {

std::vector<ComponentTime> readComponentTimes(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(path, 0, "cannot read frames.csv");
  std::string line;
  std::getline(in, line);
  std::vector<std::string> names;
  std::stringstream header(line);
  for (std::string n; std::getline(header, n, ',');) names.push_back(n);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(in, line)) {
    std::stringstream row(line);
    std::size_t k = 0;
    for (std::string cell; std::getline(row, cell, ',') && k < names.size(); ++k) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      if (end != cell.c_str() && *end == '\0') columns[names[k]].push_back(v);
    }
  }
  // (column, component, per, only rows where the component ran)
  struct Spec {
    const char *column, *component, *per;
    bool positive_only;
  };
  const Spec specs[] = {{"canny_ms", "Canny (pyramid)", "frame", false},
                        {"dt_ms", "distance transform", "frame", false},
                        {"lines_ms", "edge lines (level 0)", "frame", false},
                        {"bm_ms", "block matching", "keyframe", true},
                        {"align_ms", "edge alignment", "frame", false},
                        {"back_link_ms", "back links", "keyframe", true},
                        {"solve_ms", "optimisation (window solve)", "frame", true},
                        {"marginalize_ms", "marginalisation", "frame", true},
                        {"loop_ms", "loop closure", "keyframe", true},
                        {"total_ms", "total (incl. PNG decode, rectification)", "frame", false}};
  std::vector<ComponentTime> out;
  for (const Spec& s : specs) {
    std::vector<double> v;
    for (double x : columns[s.column])
      if (!s.positive_only || x > 0) v.push_back(x);
    if (v.empty()) continue;
    std::sort(v.begin(), v.end());
    ComponentTime c;
    c.component = s.component;
    c.per = s.per;
    double sum = 0;
    for (double x : v) sum += x;
    c.mean_ms = sum / static_cast<double>(v.size());
    c.median_ms = v[v.size() / 2];
    c.p90_ms = v[std::min(v.size() - 1, v.size() * 9 / 10)];
    c.count = v.size();
    out.push_back(c);
  }
  return out;
}

}  // namespace edgevio::pipeline
