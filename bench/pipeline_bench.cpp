// Per-component time of the whole system on one sequence, in the layout of
// the paper's Table 1: milliseconds per frame (block matching per keyframe),
// mean, median and 90th percentile over the run, plus the real-time factor
// (sequence duration / wall time) and the machine.
//
//   pipeline_bench [DATASET [MODE]]
//
// Without DATASET it renders 20 s of the `aggressive` scenario (seed 3) once
// into $TMPDIR/edgevio_pipeline_bench and reuses it. MODE defaults to edge+imu.
// The run is offline (one thread for the stages); its folder is printed.
#include <algorithm>
#include <exception>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include "edgevio/config/config.h"
#include "edgevio/pipeline/offline_run.h"
#include "edgevio/sim/simulator.h"

using namespace edgevio;
namespace fs = std::filesystem;

namespace {

std::string machine() {
  std::ifstream cpu("/proc/cpuinfo");
  std::string line;
  while (std::getline(cpu, line))
    if (line.rfind("model name", 0) == 0) return line.substr(line.find(':') + 2) + ", " + std::to_string(std::thread::hardware_concurrency()) + " cores";
  return "unknown machine";
}

/// frames.csv as columns of numbers (non-numeric cells are skipped).
std::map<std::string, std::vector<double>> readColumns(const std::string& path) {
  std::ifstream in(path);
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
  return columns;
}

void printRow(const char* what, std::vector<double> v, const char* per) {
  if (v.empty()) return;
  std::sort(v.begin(), v.end());
  double sum = 0;
  for (double x : v) sum += x;
  std::printf("| %s | %s | %.2f | %.2f | %.2f | %zu |\n", what, per, sum / static_cast<double>(v.size()), v[v.size() / 2],
              v[std::min(v.size() - 1, v.size() * 9 / 10)], v.size());
}

}  // namespace

int main(int argc, char** argv) {
  std::string dataset = argc > 1 ? argv[1] : "";
  const std::string mode = argc > 2 ? argv[2] : "edge+imu";
  const fs::path work = fs::temp_directory_path() / "edgevio_pipeline_bench";
  if (dataset.empty()) {
    dataset = (work / "aggressive").string();
    if (!fs::exists(fs::path(dataset) / "mav0" / "cam0" / "data.csv")) {
      std::printf("rendering 20 s of the aggressive scenario into %s ...\n", dataset.c_str());
      sim::SimRequest r;
      r.out_dir = dataset;
      r.scenario = "aggressive";
      r.duration_s = 20.0;
      r.seed = 3;
      sim::simulate(r, sim::SimOptions{});
    }
  }
  const std::string run_dir = (work / ("run-" + mode)).string();
  pipeline::RunSummary s;
  try {
    s = pipeline::runOffline({dataset, run_dir, mode, 0}, Config{});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  auto c = readColumns(run_dir + "/frames.csv");
  std::vector<double> bm;
  for (double x : c["bm_ms"])
    if (x > 0) bm.push_back(x);
  std::vector<double> solve, marg;
  for (double x : c["solve_ms"])
    if (x > 0) solve.push_back(x);
  for (double x : c["marginalize_ms"])
    if (x > 0) marg.push_back(x);
  std::printf("# edgevio per-component time, mode %s\n\n%s\nmachine: %s\n%zu frames, %zu keyframes, %s\n\n", mode.c_str(),
              dataset.c_str(), machine().c_str(), s.frames, s.keyframes, s.failed ? ("FAILED: " + s.failure).c_str() : "tracking ok");
  std::printf("| component | per | mean [ms] | median [ms] | p90 [ms] | count |\n|---|---|---:|---:|---:|---:|\n");
  printRow("Canny (pyramid)", c["canny_ms"], "frame");
  printRow("distance transform", c["dt_ms"], "frame");
  printRow("edge lines (level 0)", c["lines_ms"], "frame");
  printRow("block matching", bm, "keyframe");
  printRow("edge alignment", c["align_ms"], "frame");
  printRow("optimisation (window solve)", solve, "frame");
  printRow("marginalisation", marg, "frame");
  std::vector<double> loop_ms;
  for (double x : c["loop_ms"])
    if (x > 0) loop_ms.push_back(x);
  printRow("loop closure", loop_ms, "keyframe");
  printRow("total (incl. PNG decode, rectification)", c["total_ms"], "frame");
  std::printf("\nsequence %.1f s, wall %.1f s, real-time factor %.2f (one thread; run folder %s)\n", s.duration_s, s.wall_s,
              s.realtime_factor, run_dir.c_str());
  return s.failed ? 1 : 0;
}
