// Per-component time of the whole system on one sequence, in the layout of
// the paper's Table 1: milliseconds per frame (block matching per keyframe),
// mean, median and 90th percentile over the run, plus the real-time factor
// (sequence duration / wall time) and the machine.
//
//   pipeline_bench [DATASET [MODE]]
//
// Without DATASET it renders 20 s of the `aggressive` scenario (seed 3) once
// into $TMPDIR/edgevio_pipeline_bench and reuses it. MODE defaults to edge+imu.
// The run is offline (three pipeline threads; component times include their
// contention for the cores); its folder is printed.
#include <exception>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "edgevio/common/process_memory.h"
#include "edgevio/config/config.h"
#include "edgevio/pipeline/component_times.h"
#include "edgevio/pipeline/run.h"
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

}  // namespace

int main(int argc, char** argv) {
  edgevio::keepFreedMemory();
  std::string dataset = argc > 1 ? argv[1] : "";
  const std::string mode = argc > 2 ? argv[2] : "edge+imu";
  const std::optional<pipeline::Mode> parsed_mode = pipeline::parseMode(mode);
  if (!parsed_mode) {
    std::fprintf(stderr, "error: unknown mode '%s': use %s\n", mode.c_str(), pipeline::kModeNames);
    return 2;
  }
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
    s = pipeline::run({dataset, run_dir, *parsed_mode}, Config{});
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  std::printf("# edgevio per-component time, mode %s\n\n%s\nmachine: %s\n%zu frames, %zu keyframes, %s\n\n", mode.c_str(),
              dataset.c_str(), machine().c_str(), s.frames, s.keyframes, s.failed ? ("FAILED: " + s.failure).c_str() : "tracking ok");
  std::printf("| component | per | mean [ms] | median [ms] | p90 [ms] | count |\n|---|---|---:|---:|---:|---:|\n");
  for (const pipeline::ComponentTime& c : pipeline::readComponentTimes(run_dir + "/frames.csv"))
    if (c.count > 0)
      std::printf("| %s | %s | %.2f | %.2f | %.2f | %zu |\n", c.component.c_str(), c.per.c_str(), c.mean_ms, c.median_ms,
                c.p90_ms, c.count);
  std::printf("\nsequence %.1f s, wall %.1f s, real-time factor %.2f (three threads on this machine's cores: component times include their contention; run folder %s)\n", s.duration_s, s.wall_s,
              s.realtime_factor, run_dir.c_str());
  return s.failed ? 1 : 0;
}
