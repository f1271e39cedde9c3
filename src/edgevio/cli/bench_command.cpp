// `edgevio bench MATRIX.yaml --out DIR`: sequences x modes x skips.
//
// MATRIX.yaml (relative paths are relative to the matrix file's folder):
//   modes: [edge-only, edge+imu+loop]     # any of the four
//   skips: [0, 3]                         # --skip values
//   config: my.yaml                       # optional, for every run
//   sequences:
//     - {name: agg, scenario: aggressive, duration: 20, seed: 3}                 # rendered once
//     - {name: v202, trajectory: path/gt.csv, imu: path/imu0.csv, start: 0, duration: 30}
//     - {name: mine, dataset: path/to/asl/folder}                               # an existing folder
//
// Every run is one self-contained shell command (render the sequence under a
// lock if it is missing, then `edgevio run`), so `--emit-jobs` can hand the
// commands to any scheduler and `--jobs N` runs N of them here. The report
// (DIR/report.md, DIR/report.csv) is `edgevio eval --results DIR/runs` plus
// the per-component time table of every run and an SVG plot per run.
#include <atomic>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <mutex>
#include <ostream>
#include <thread>

#include "edgevio/cli/commands.h"
#include "edgevio/common/error.h"
#include "edgevio/common/yaml_file.h"
#include "edgevio/config/config.h"
#include "edgevio/eval/batch.h"
#include "edgevio/eval/svg_plot.h"
#include "edgevio/pipeline/component_times.h"
#include "edgevio/pipeline/frame_record.h"
#include "edgevio/pipeline/mode.h"

namespace edgevio::cli {

namespace fs = std::filesystem;

namespace {

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

struct Job {
  std::string folder;   ///< run folder
  std::string command;  ///< one shell command line
  std::string sequence, mode;
};

std::vector<Job> planJobs(const std::string& matrix_path, const std::string& out, const std::string& exe) {
  const YAML::Node m = loadYamlFile(matrix_path);
  const fs::path base = fs::absolute(matrix_path).parent_path();
  const auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() ? p : (base / p).lexically_normal().string(); };
  std::vector<std::string> modes = {"edge+imu+loop"};
  std::vector<int> skips = {0};
  if (m["modes"]) {
    modes.clear();
    for (const auto& n : m["modes"]) {
      const std::string mode = n.as<std::string>();
      if (!pipeline::parseMode(mode))
        throw InputError(matrix_path, yamlLine(n), "unknown mode '" + mode + "': use " + pipeline::kModeNames);
      modes.push_back(mode);
    }
  }
  if (m["skips"]) {
    skips.clear();
    for (const auto& n : m["skips"]) {
      int k = -1;
      if (!YAML::convert<int>::decode(n, k) || k < 0) throw InputError(matrix_path, yamlLine(n), "skips: integers >= 0");
      skips.push_back(k);
    }
  }
  const std::string config = m["config"] ? resolve(yamlString(m, "config", matrix_path)) : "";
  if (!m["sequences"] || !m["sequences"].IsSequence() || m["sequences"].size() == 0)
    throw InputError(matrix_path, yamlLine(m), "needs a non-empty 'sequences' list");
  const fs::path out_abs = fs::absolute(out);
  std::vector<Job> jobs;
  for (const auto& s : m["sequences"]) {
    const std::string name = yamlString(s, "name", matrix_path);
    if (name.empty() || name.find_first_of("/ '") != std::string::npos)
      throw InputError(matrix_path, yamlLine(s), "sequence name '" + name + "': no slashes, spaces or quotes");
    std::string dataset, prepare;
    if (s["dataset"]) {
      dataset = resolve(yamlString(s, "dataset", matrix_path));
    } else if (s["scenario"] || s["trajectory"]) {
      dataset = (out_abs / "data" / name).string();
      std::string sim = quote(exe) + " simulate --out " + quote(dataset);
      if (s["scenario"]) sim += " --scenario " + quote(yamlString(s, "scenario", matrix_path));
      if (s["trajectory"]) sim += " --trajectory " + quote(resolve(yamlString(s, "trajectory", matrix_path)));
      if (s["imu"]) sim += " --imu " + quote(resolve(yamlString(s, "imu", matrix_path)));
      for (const char* key : {"start", "duration", "seed", "blur_ms"})
        if (s[key]) {
          std::string flag = key;
          if (flag == "blur_ms") flag = "blur-ms";
          char value[32];
          std::snprintf(value, sizeof value, "%.10g", yamlDouble(s, key, matrix_path));
          sim += " --" + flag + " " + value;
        }
      const std::string done = dataset + "/.complete";
      prepare = "mkdir -p " + quote((out_abs / "data").string()) + " && flock " + quote(dataset + ".lock") + " sh -c " +
                quote("[ -f " + quote(done) + " ] || { " + sim + " > " + quote(dataset + ".log") + " 2>&1 && touch " + quote(done) + "; }") +
                " && ";
    } else {
      throw InputError(matrix_path, yamlLine(s), "sequence '" + name + "' needs dataset, scenario or trajectory");
    }
    for (const std::string& mode : modes)
      for (int k : skips) {
        const fs::path folder = out_abs / "runs" / name / (mode + "-skip" + std::to_string(k));
        std::string run = quote(exe) + " run " + quote(dataset) + " --out " + quote(folder.string()) + " --mode " + quote(mode) +
                          " --skip " + std::to_string(k);
        if (!config.empty()) run += " --config " + quote(config);
        jobs.push_back({folder.string(),
                        prepare + "mkdir -p " + quote(folder.string()) + " && " + run + " > " + quote(folder.string() + "/run.log") + " 2>&1",
                        name, mode});
      }
  }
  return jobs;
}

void writeTimingTable(std::ostream& out, const std::vector<eval::RunEvaluation>& runs, const std::string& runs_dir) {
  out << "\n## Time per component [ms, mean]\n\nPer frame, except those marked per keyframe; one thread per run.\n\n| sequence | mode |";
  std::string rule = "|---|---|";
  for (const pipeline::FrameColumn& c : pipeline::frameColumns())
    if (c.component.name) {
      out << " " << c.component.name << (std::string(c.component.per) == "keyframe" ? " (per keyframe)" : "") << " |";
      rule += "---:|";
    }
  out << "\n" << rule << "\n";
  for (const auto& r : runs) {
    std::vector<pipeline::ComponentTime> times;
    try {
      times = pipeline::readComponentTimes(runs_dir + "/" + r.folder + "/frames.csv");
    } catch (const InputError&) {
      continue;
    }
    out << "| " << r.sequence << " | " << r.mode << " |";
    for (const pipeline::ComponentTime& c : times) {
      char b[32];
      std::snprintf(b, sizeof b, "%.2f", c.mean_ms);
      out << " " << (c.count > 0 ? b : "-") << " |";
    }
    out << "\n";
  }
}

}  // namespace

int bench(const BenchArgs& a, std::ostream& out, std::ostream& err) {
  try {
    if (a.matrix.empty() || a.out.empty()) throw InputError("bench needs MATRIX.yaml and --out DIR");
    const std::string exe = fs::read_symlink("/proc/self/exe").string();
    const std::vector<Job> jobs = planJobs(a.matrix, a.out, exe);
    if (a.emit_jobs) {
      for (const Job& j : jobs) out << j.command << "\n";
      return kExitOk;
    }
    fs::create_directories(fs::path(a.out) / "runs");
    std::atomic<std::size_t> next{0}, done{0};
    std::mutex print;
    std::vector<std::thread> workers;
    const int n = std::max(1, a.jobs);
    for (int w = 0; w < n; ++w)
      workers.emplace_back([&] {
        for (std::size_t i = next++; i < jobs.size(); i = next++) {
          const int rc = std::system(jobs[i].command.c_str());
          if (!fs::exists(fs::path(jobs[i].folder) / "summary.json")) {
            // The run never started (rendering failed, bad dataset): a failure row, never a missing one.
            fs::create_directories(jobs[i].folder);
            std::ofstream js(fs::path(jobs[i].folder) / "summary.json");
            js << "{\"sequence\": \"" << jobs[i].sequence << "\", \"mode\": \"" << jobs[i].mode
               << "\", \"failed\": true, \"failure\": \"no result (exit status " << rc << "; see run.log and data/*.log)\"}\n";
          }
          const std::lock_guard<std::mutex> lock(print);
          err << "[" << ++done << "/" << jobs.size() << "] " << fs::relative(jobs[i].folder, a.out).string()
              << (rc == 0 ? "" : " (exit status " + std::to_string(rc) + ", see run.log)") << "\n";
        }
      });
    for (auto& t : workers) t.join();

    const std::string runs_dir = (fs::path(a.out) / "runs").string();
    const Config config;
    const auto runs = eval::evaluateRunFolders(runs_dir, config.eval);
    for (const auto& r : runs)
      if (r.ok) eval::writeSvgPlot(runs_dir + "/" + r.folder + "/eval.svg", r.result, r.sequence + ", " + r.mode);
    std::ofstream md(fs::path(a.out) / "report.md"), csv(fs::path(a.out) / "report.csv");
    if (!md || !csv) throw InputError(a.out, 0, "cannot write report.md / report.csv");
    eval::writeReportMarkdown(md, runs, config.eval);
    writeTimingTable(md, runs, runs_dir);
    eval::writeReportCsv(csv, runs);
    eval::writeReportMarkdown(out, runs, config.eval);
    writeTimingTable(out, runs, runs_dir);
    out << "\nreport: " << (fs::path(a.out) / "report.md").string() << ", plots: <run folder>/eval.svg\n";
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  } catch (const YAML::Exception& e) {
    err << "error: " << a.matrix << ": " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
