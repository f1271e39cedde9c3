// `edgevio bench MATRIX.yaml --out DIR`: sequences x modes x skips.
//
// MATRIX.yaml (relative paths are relative to the matrix file's folder):
//   modes: [edge-only, edge+imu+loop]     # any of the four
//   skips: [0, 3]                         # --skip values
//   skip_offsets: all                     # first (default): from frame 0; all: each K from frames 0..K too
//   config: my.yaml                       # optional, for every run
//   sequences:
//     - {name: agg, scenario: aggressive, duration: 20, seed: 3}                 # rendered once
//     - {name: v102, trajectory: path/gt.csv, imu: path/imu0.csv, seeds: [1, 2, 3]}  # one render per seed
//     - {name: v202, trajectory: path/gt.csv, imu: path/imu0.csv, start: 0, duration: 30}
//     - {name: mine, dataset: path/to/asl/folder}                               # an existing folder
//     - {name: dark, scenario: figure8, duration: 20, seed: 1, faults: ["black:at=5,for=0.5"]}  # simulate --fault
//
// Every run is one self-contained shell command (render the sequence under a
// lock if it is missing, then `edgevio run`), so `--emit-jobs` can hand the
// commands to any scheduler and `--jobs N` runs N of them here. The report
// (DIR/report.md, DIR/report.csv) is `edgevio eval --results DIR/runs` plus
// the per-component time table of every run and an SVG plot per run;
// DIR/tables.md holds the results tables (ATE by mode, seeds side by side;
// by frame skip) that scripts/results.sh puts into the README.
#include <atomic>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <ostream>
#include <thread>

#include "edgevio/cli/commands.h"
#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/yaml_file.h"
#include "edgevio/config/config.h"
#include "edgevio/eval/batch.h"
#include "edgevio/eval/svg_plot.h"
#include "edgevio/pipeline/component_times.h"
#include "edgevio/pipeline/frame_record.h"
#include "edgevio/pipeline/mode.h"
#include "edgevio/sim/faults.h"

namespace edgevio::cli {

namespace fs = std::filesystem;

namespace {

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

/// One sequence of a matrix: its name, the label its results are grouped
/// under (the entry's name; a seed's run is "<name>-seed<k>"), where its
/// dataset is and the shell command that renders it when it is missing.
struct MatrixSequence {
  std::string name, group, dataset, prepare;
};

/// The tables of DIR/tables.md (`tables:` in the matrix).
enum class Table { kAteByMode, kAteBySkip, kTime };
inline constexpr options::Choice<Table> kTableChoices[] = {
    {Table::kAteByMode, "ate_by_mode", "ATE per sequence and mode, seeds side by side, at the first skip from frame 0"},
    {Table::kAteBySkip, "ate_by_skip", "ATE per sequence and mode against the frame skip (offsets side by side)"},
    {Table::kTime, "time", "time per component and real-time factor of every run"}};

/// Which of the K+1 interleaved frame subsets a skip K runs (`skip_offsets:`).
enum class SkipOffsets { kFirst, kAll };
inline constexpr options::Choice<SkipOffsets> kSkipOffsetChoices[] = {
    {SkipOffsets::kFirst, "first", "from frame 0 only"},
    {SkipOffsets::kAll, "all", "from each of frames 0..K too: together they use every frame once"}};

struct Matrix {
  std::vector<std::string> modes = {"edge+imu+loop"};
  std::vector<int> skips = {0};
  SkipOffsets skip_offsets = SkipOffsets::kFirst;
  std::string config;  ///< for every run; empty: defaults
  std::vector<MatrixSequence> sequences;
  std::vector<Table> tables = {Table::kAteByMode, Table::kAteBySkip};
};

struct Job {
  std::string folder;   ///< run folder
  std::string command;  ///< one shell command line
  std::string sequence, group, mode;
  int skip = 0, skip_offset = 0;
};

/// The `simulate` command line of a rendered sequence entry.
std::string renderCommand(const YAML::Node& s, const std::string& matrix_path, const std::string& exe, const std::string& dataset,
                          const std::function<std::string(const std::string&)>& resolve, const std::string& seed) {
  std::string sim = quote(exe) + " simulate --out " + quote(dataset);
  if (s["scenario"]) sim += " --scenario " + quote(yamlString(s, "scenario", matrix_path));
  if (s["trajectory"]) sim += " --trajectory " + quote(resolve(yamlString(s, "trajectory", matrix_path)));
  if (s["imu"]) sim += " --imu " + quote(resolve(yamlString(s, "imu", matrix_path)));
  for (const char* key : {"start", "duration", "blur_ms"})
    if (s[key]) {
      sim += std::string(" --") + (std::string(key) == "blur_ms" ? "blur-ms" : key) + " " +
             formatText("%.10g", yamlDouble(s, key, matrix_path));
    }
  if (!seed.empty()) sim += " --seed " + seed;
  if (const YAML::Node faults = s["faults"]) {
    if (!faults.IsSequence()) throw InputError(matrix_path, yamlLine(faults), "faults: a list of simulate --fault specs");
    for (const auto& f : faults) {
      if (!f.IsScalar()) throw InputError(matrix_path, yamlLine(f), "faults: each a simulate --fault spec such as black:at=5,for=0.5");
      const std::string spec = f.Scalar();
      try {
        sim::parseFault(spec);
      } catch (const InputError& e) {
        throw InputError(matrix_path, yamlLine(f), e.what());
      }
      sim += " --fault " + quote(spec);
    }
  }
  // Rendered once, under a lock, whichever job needs it first.
  const std::string done = dataset + "/.complete";
  return "mkdir -p " + quote(fs::path(dataset).parent_path().string()) + " && flock " + quote(dataset + ".lock") + " sh -c " +
         quote("[ -f " + quote(done) + " ] || { " + sim + " > " + quote(dataset + ".log") + " 2>&1 && touch " + quote(done) + "; }") +
         " && ";
}

/// The seeds of an entry: `seeds: [1, 2, 3]`, `seed: 1`, or none ("").
std::vector<std::string> seedsOf(const YAML::Node& s, const std::string& matrix_path) {
  std::vector<std::string> seeds;
  if (s["seed"]) seeds.push_back(std::to_string(static_cast<long long>(yamlDouble(s, "seed", matrix_path))));
  if (s["seeds"]) {
    if (!s["seeds"].IsSequence() || s["seeds"].size() == 0) throw InputError(matrix_path, yamlLine(s["seeds"]), "seeds: a list of integers");
    for (const auto& n : s["seeds"]) {
      long long k = 0;
      if (!YAML::convert<long long>::decode(n, k) || k < 0) throw InputError(matrix_path, yamlLine(n), "seeds: integers >= 0");
      seeds.push_back(std::to_string(k));
    }
  }
  if (seeds.empty()) seeds.push_back("");
  return seeds;
}

std::vector<MatrixSequence> readSequences(const YAML::Node& m, const std::string& matrix_path, const std::string& out,
                                          const std::string& exe) {
  const fs::path base = fs::absolute(matrix_path).parent_path();
  const auto resolve = [&](const std::string& p) { return fs::path(p).is_absolute() ? p : (base / p).lexically_normal().string(); };
  if (!m["sequences"] || !m["sequences"].IsSequence() || m["sequences"].size() == 0)
    throw InputError(matrix_path, yamlLine(m), "needs a non-empty 'sequences' list");
  std::vector<MatrixSequence> sequences;
  for (const auto& s : m["sequences"]) {
    const std::string name = yamlString(s, "name", matrix_path);
    if (name.empty() || name.find_first_of("/ '") != std::string::npos)
      throw InputError(matrix_path, yamlLine(s), "sequence name '" + name + "': no slashes, spaces or quotes");
    if (s["dataset"]) {
      sequences.push_back({name, name, resolve(yamlString(s, "dataset", matrix_path)), ""});
      continue;
    }
    if (!s["scenario"] && !s["trajectory"])
      throw InputError(matrix_path, yamlLine(s), "sequence '" + name + "' needs dataset, scenario or trajectory");
    const std::vector<std::string> seeds = seedsOf(s, matrix_path);
    for (const std::string& seed : seeds) {
      const std::string run_name = s["seeds"] ? name + "-seed" + seed : name;
      const std::string dataset = (fs::absolute(out) / "data" / run_name).string();
      sequences.push_back({run_name, name, dataset, renderCommand(s, matrix_path, exe, dataset, resolve, seed)});
    }
  }
  return sequences;
}

Matrix readMatrix(const std::string& matrix_path, const std::string& out, const std::string& exe) {
  const YAML::Node m = loadYamlFile(matrix_path);
  Matrix matrix;
  if (m["modes"]) {
    matrix.modes.clear();
    for (const auto& n : m["modes"]) {
      const std::string mode = n.IsScalar() ? n.Scalar() : std::string();
      if (!pipeline::parseMode(mode))
        throw InputError(matrix_path, yamlLine(n), "unknown mode '" + mode + "': use " + pipeline::kModeNames);
      matrix.modes.push_back(mode);
    }
  }
  if (m["skips"]) {
    matrix.skips.clear();
    for (const auto& n : m["skips"]) {
      int k = -1;
      if (!YAML::convert<int>::decode(n, k) || k < 0) throw InputError(matrix_path, yamlLine(n), "skips: integers >= 0");
      matrix.skips.push_back(k);
    }
  }
  if (const YAML::Node n = m["skip_offsets"];
      n && (!n.IsScalar() || !options::parseChoice(kSkipOffsetChoices, n.Scalar(), &matrix.skip_offsets)))
    throw InputError(matrix_path, yamlLine(n), "skip_offsets: one of " + options::choiceList(kSkipOffsetChoices));
  if (m["tables"]) {
    matrix.tables.clear();
    for (const auto& n : m["tables"]) {
      Table t{};
      if (!n.IsScalar() || !options::parseChoice(kTableChoices, n.Scalar(), &t))
        throw InputError(matrix_path, yamlLine(n), "tables: each one of " + options::choiceList(kTableChoices));
      matrix.tables.push_back(t);
    }
  }
  if (m["config"]) {
    const std::string c = yamlString(m, "config", matrix_path);
    matrix.config = fs::path(c).is_absolute() ? c : (fs::absolute(matrix_path).parent_path() / c).lexically_normal().string();
  }
  matrix.sequences = readSequences(m, matrix_path, out, exe);
  return matrix;
}

std::vector<Job> planJobs(const Matrix& matrix, const std::string& out, const std::string& exe) {
  std::vector<Job> jobs;
  for (const MatrixSequence& s : matrix.sequences)
    for (const std::string& mode : matrix.modes)
      for (int k : matrix.skips)
        for (int p = 0; p <= (matrix.skip_offsets == SkipOffsets::kAll ? k : 0); ++p) {
          const std::string offset = p > 0 ? "-from" + std::to_string(p) : "";
          const fs::path folder = fs::absolute(out) / "runs" / s.name / (mode + "-skip" + std::to_string(k) + offset);
          // No alignment pictures: a matrix's runs are for its tables, and
          // their times stay those of the estimator alone.
          std::string run = quote(exe) + " run " + quote(s.dataset) + " --out " + quote(folder.string()) + " --mode " + quote(mode) +
                            " --skip " + std::to_string(k) + (p > 0 ? " --skip-offset " + std::to_string(p) : "") + " --pictures-every 0";
          if (!matrix.config.empty()) run += " --config " + quote(matrix.config);
          jobs.push_back({folder.string(),
                          s.prepare + "mkdir -p " + quote(folder.string()) + " && " + run + " > " + quote(folder.string() + "/run.log") +
                              " 2>&1",
                          s.name, s.group, mode, k, p});
        }
  return jobs;
}

/// A run's cell in a results table: its ATE, or why it has none.
std::string ateCell(const eval::RunEvaluation* r) {
  if (!r) return "-";
  if (!r->ok) return "**failed**";
  if (r->lost_intervals > 0) return formatText("%.3f (lost %.1f s)", r->result.ate_rmse_m, r->lost_s);
  return formatText("%.3f", r->result.ate_rmse_m);
}

/// The run of a job among the evaluated runs (null when it left no folder).
const eval::RunEvaluation* runOf(const Job& j, const std::vector<eval::RunEvaluation>& runs, const std::string& runs_dir) {
  const std::string folder = fs::relative(j.folder, runs_dir).string();
  for (const auto& r : runs)
    if (r.folder == folder) return &r;
  return nullptr;
}

/// The ATE cells of the jobs `pick` selects, side by side: "a / b".
std::string ateCells(const std::vector<Job>& jobs, const std::function<bool(const Job&)>& pick,
                     const std::vector<eval::RunEvaluation>& runs, const std::string& runs_dir) {
  std::string cells;
  for (const Job& j : jobs)
    if (pick(j)) cells += (cells.empty() ? "" : " / ") + ateCell(runOf(j, runs, runs_dir));
  return cells;
}

/// ATE [m] per sequence (its seeds side by side) and mode, at the first skip.
void writeAteByMode(std::ostream& out, const Matrix& matrix, const std::vector<Job>& jobs, const std::vector<eval::RunEvaluation>& runs,
                    const std::string& runs_dir) {
  std::vector<std::string> groups;
  for (const MatrixSequence& s : matrix.sequences)
    if (std::find(groups.begin(), groups.end(), s.group) == groups.end()) groups.push_back(s.group);
  out << "\n| sequence |";
  for (const std::string& mode : matrix.modes) out << " " << mode << " |";
  out << "\n|---|";
  for (std::size_t k = 0; k < matrix.modes.size(); ++k) out << "---:|";
  out << "\n";
  for (const std::string& g : groups) {
    out << "| " << g << " |";
    for (const std::string& mode : matrix.modes) {
      const auto pick = [&](const Job& j) { return j.group == g && j.mode == mode && j.skip == matrix.skips[0] && j.skip_offset == 0; };
      out << " " << ateCells(jobs, pick, runs, runs_dir) << " |";
    }
    out << "\n";
  }
}

/// ATE [m] per sequence and mode against the frame skip K (with
/// `skip_offsets: all`, the runs from frames 0..K side by side).
void writeAteBySkip(std::ostream& out, const Matrix& matrix, const std::vector<Job>& jobs, const std::vector<eval::RunEvaluation>& runs,
                    const std::string& runs_dir) {
  out << "\n| sequence | mode |";
  for (int k : matrix.skips) {
    out << " K=" << k;
    if (matrix.skip_offsets == SkipOffsets::kAll && k > 0) {
      out << ", from frame 0";
      for (int p = 1; p <= k; ++p) out << " / " << p;
    }
    out << " |";
  }
  out << "\n|---|---|";
  for (std::size_t k = 0; k < matrix.skips.size(); ++k) out << "---:|";
  out << "\n";
  for (const MatrixSequence& s : matrix.sequences)
    for (const std::string& mode : matrix.modes) {
      out << "| " << s.name << " | " << mode << " |";
      for (int k : matrix.skips) {
        const auto pick = [&](const Job& j) { return j.sequence == s.name && j.mode == mode && j.skip == k; };
        out << " " << ateCells(jobs, pick, runs, runs_dir) << " |";
      }
      out << "\n";
    }
}

/// Time per component [ms, mean] of every run (per frame, but for those per
/// keyframe), its real-time factor and its latency percentiles.
void writeTimingTable(std::ostream& out, const std::vector<eval::RunEvaluation>& runs, const std::string& runs_dir) {
  out << "\n| sequence | mode |";
  std::string rule = "|---|---|";
  for (const pipeline::FrameColumn& c : pipeline::frameColumns())
    if (c.component.name) {
      out << " " << c.component.name << (std::string(c.component.per) == "keyframe" ? " (per keyframe)" : "") << " |";
      rule += "---:|";
    }
  out << " real-time factor | latency p50 / p99 [ms] |\n" << rule << "---:|---:|\n";
  for (const auto& r : runs) {
    std::vector<pipeline::ComponentTime> times;
    try {
      times = pipeline::readComponentTimes(runs_dir + "/" + r.folder + "/frames.csv");
    } catch (const InputError&) {
      continue;
    }
    out << "| " << r.sequence << " | " << eval::runLabel(r) << " |";
    for (const pipeline::ComponentTime& c : times) out << " " << (c.count > 0 ? formatText("%.2f", c.mean_ms) : "-") << " |";
    out << formatText(" %.1f |", r.realtime_factor);
    out << " " << (std::isfinite(r.latency_p50_ms) ? formatText("%.1f / %.1f", r.latency_p50_ms, r.latency_p99_ms) : "-")
        << " |\n";
  }
}

/// DIR/tables.md: the tables the matrix asks for.
void writeResultTables(std::ostream& out, const Matrix& matrix, const std::vector<Job>& jobs,
                       const std::vector<eval::RunEvaluation>& runs, const std::string& runs_dir) {
  for (const Table t : matrix.tables) {
    if (t == Table::kAteByMode) writeAteByMode(out, matrix, jobs, runs, runs_dir);
    if (t == Table::kAteBySkip && matrix.skips.size() > 1) writeAteBySkip(out, matrix, jobs, runs, runs_dir);
    if (t == Table::kTime) writeTimingTable(out, runs, runs_dir);
  }
}

}  // namespace

int bench(const BenchArgs& a, std::ostream& out, std::ostream& err) {
  try {
    if (a.matrix.empty() || a.out.empty()) throw InputError("bench needs MATRIX.yaml and --out DIR");
    const std::string exe = fs::read_symlink("/proc/self/exe").string();
    const Matrix matrix = readMatrix(a.matrix, a.out, exe);
    const std::vector<Job> jobs = planJobs(matrix, a.out, exe);
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
    md << "\n## Time per component [ms, mean]\n";
    writeTimingTable(md, runs, runs_dir);
    eval::writeReportCsv(csv, runs);
    std::ofstream tables(fs::path(a.out) / "tables.md");
    writeResultTables(tables, matrix, jobs, runs, runs_dir);
    eval::writeReportMarkdown(out, runs, config.eval);
    out << "\n## Time per component [ms, mean]\n";
    writeTimingTable(out, runs, runs_dir);
    out << "\n## Results tables\n";
    writeResultTables(out, matrix, jobs, runs, runs_dir);
    out << "\nreport: " << (fs::path(a.out) / "report.md").string() << ", tables: " << (fs::path(a.out) / "tables.md").string()
        << ", plots: <run folder>/eval.svg\n";
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
