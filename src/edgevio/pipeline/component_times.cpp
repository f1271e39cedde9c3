#include "edgevio/pipeline/component_times.h"

#include <algorithm>

#include "edgevio/common/table_reader.h"
#include "edgevio/pipeline/frame_record.h"

namespace edgevio::pipeline {

std::vector<ComponentTime> readComponentTimes(const std::string& path) {
  TableReader in(path, TableReader::Separator::kComma, TableReader::Header::kColumnNames);
  std::vector<const FrameColumn*> timed;
  std::vector<std::size_t> index;
  for (const FrameColumn& c : frameColumns())
    if (c.component.name) {
      timed.push_back(&c);
      index.push_back(in.column(c.name));
    }
  std::vector<std::vector<double>> samples(timed.size());
  while (in.next())
    for (std::size_t k = 0; k < timed.size(); ++k) {
      const double v = in.number(index[k]);
      if (!timed[k]->component.when_run || v > 0) samples[k].push_back(v);
    }
  std::vector<ComponentTime> out;
  for (std::size_t k = 0; k < timed.size(); ++k) {
    std::vector<double>& v = samples[k];
    ComponentTime c;
    c.component = timed[k]->component.name;
    c.per = timed[k]->component.per;
    c.count = v.size();
    if (!v.empty()) {
      std::sort(v.begin(), v.end());
      double sum = 0;
      for (double x : v) sum += x;
      c.mean_ms = sum / static_cast<double>(v.size());
      c.median_ms = v[v.size() / 2];
      c.p90_ms = v[std::min(v.size() - 1, v.size() * 9 / 10)];
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace edgevio::pipeline
