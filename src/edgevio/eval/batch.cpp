#include "edgevio/eval/batch.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <ostream>
#include <set>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/time.h"
#include "edgevio/common/yaml_file.h"

namespace edgevio::eval {

namespace fs = std::filesystem;

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string scalarOr(const YAML::Node& root, const char* key, const std::string& fallback) {
  const YAML::Node n = root[key];
  return n && n.IsScalar() ? n.Scalar() : fallback;
}

std::string findGroundTruth(const fs::path& run, const YAML::Node& summary) {
  const std::string gt = scalarOr(summary, "groundtruth", "");
  if (!gt.empty()) {
    const fs::path p = fs::path(gt).is_absolute() ? fs::path(gt) : run / gt;
    return p.string();
  }
  const std::string dataset = scalarOr(summary, "dataset", "");
  if (!dataset.empty()) {
    fs::path d = fs::path(dataset).is_absolute() ? fs::path(dataset) : run / dataset;
    if (fs::is_directory(d / "mav0")) d /= "mav0";
    return (d / "state_groundtruth_estimate0" / "data.csv").string();
  }
  for (const char* name : {"groundtruth.csv", "groundtruth_tum.txt", "groundtruth.txt"})
    if (fs::exists(run / name)) return (run / name).string();
  return "";
}

RunEvaluation evaluateRun(const fs::path& dir, const fs::path& run, const EvalOptions& options) {
  RunEvaluation r;
  r.folder = fs::relative(run, dir).string();
  if (r.folder == ".") r.folder = run.filename().string();
  r.sequence = r.folder;
  r.mode = "-";
  r.realtime_factor = r.peak_rss_mb = r.latency_p50_ms = r.latency_p99_ms = kNaN;
  YAML::Node summary(YAML::NodeType::Map);
  try {
    if (fs::exists(run / "summary.json")) summary = loadYamlFile((run / "summary.json").string());
    r.sequence = scalarOr(summary, "sequence", r.sequence);
    r.mode = scalarOr(summary, "mode", r.mode);
    const auto number = [](const YAML::Node& n, double fallback) {
      double v = 0.0;
      return n && n.IsScalar() && std::sscanf(n.Scalar().c_str(), "%lf", &v) == 1 ? v : fallback;
    };
    r.realtime_factor = number(summary["realtime_factor"], kNaN);
    r.peak_rss_mb = number(summary["peak_rss_mb"], kNaN);
    r.skip = static_cast<int>(number(summary["skip"], 0.0));
    r.skip_offset = static_cast<int>(number(summary["skip_offset"], 0.0));
    if (const YAML::Node latency = summary["latency_ms"]; latency && latency.IsMap()) {
      r.latency_p50_ms = number(latency["p50"], kNaN);
      r.latency_p99_ms = number(latency["p99"], kNaN);
    }
    std::vector<std::pair<double, double>> lost_spans;
    if (const YAML::Node lost = summary["lost_intervals"]; lost && lost.IsSequence())
      for (const YAML::Node& l : lost) {
        lost_spans.emplace_back(number(l["start_s"], 0.0), number(l["end_s"], 0.0));
        ++r.lost_intervals;
        r.lost_s += lost_spans.back().second - lost_spans.back().first;
        r.longest_loss_s = std::max(r.longest_loss_s, lost_spans.back().second - lost_spans.back().first);
      }
    r.frames = static_cast<long long>(number(summary["frames"], -1));
    r.frames_to_process = static_cast<long long>(number(summary["frames_to_process"], -1));
    if (summary["unaccounted_frames"]) r.unaccounted_frames = static_cast<long long>(number(summary["unaccounted_frames"], 0));
    if (scalarOr(summary, "failed", "false") == "true") {
      r.failure = "run reported failure (summary.json: failed = true)";
      const std::string why = scalarOr(summary, "failure", "");
      if (!why.empty()) r.failure += ": " + why;
      return r;
    }
    const fs::path est = run / "trajectory_tum.txt";
    if (!fs::exists(est)) {
      r.failure = "no trajectory_tum.txt";
      return r;
    }
    const std::string gt = findGroundTruth(run, summary);
    if (gt.empty()) {
      r.failure = "no ground truth found (summary.json groundtruth/dataset, or groundtruth.csv in the folder)";
      return r;
    }
    const io::Trajectory truth = io::readTrajectory(gt), estimate = io::readTrajectory(est.string());
    r.result = evaluate(truth, estimate, options);
    if (!lost_spans.empty())
      for (const io::Trajectory& segment : segmentsBetweenLosses(estimate, lost_spans)) {
        try {
          r.segment_ate_m.push_back(evaluate(truth, segment, options).ate_rmse_m);
        } catch (const InputError&) {
          // A segment the ground truth does not cover has no ATE; the whole run's is reported above.
        }
      }
    r.ok = true;
  } catch (const InputError& e) {
    r.failure = e.what();
  }
  return r;
}

std::string num(double v, int decimals) {
  if (!std::isfinite(v)) return "-";
  return formatText("%.*f", decimals, v);
}

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string r = "\"";
  for (char c : s) r += c == '"' ? std::string("\"\"") : std::string(1, c == '\n' ? ' ' : c);
  return r + "\"";
}

}  // namespace

std::vector<io::Trajectory> segmentsBetweenLosses(const io::Trajectory& est, const std::vector<std::pair<double, double>>& lost) {
  std::vector<io::Trajectory> segments(1);
  std::size_t next = 0;  // the first lost interval not yet passed
  for (const io::TrajectorySample& s : est) {
    const double t = toSeconds(s.t_ns - est.front().t_ns);
    while (next < lost.size() && t > lost[next].second) {
      ++next;
      segments.emplace_back();
    }
    if (next < lost.size() && t >= lost[next].first) continue;  // inside a loss
    segments.back().push_back(s);
  }
  std::vector<io::Trajectory> kept;
  for (io::Trajectory& seg : segments)
    if (seg.size() >= kMinSegmentPoses) kept.push_back(std::move(seg));
  return kept;
}

RunEvaluation evaluateRunFolder(const std::string& run_dir, const EvalOptions& options) {
  fs::path run = fs::absolute(run_dir).lexically_normal();
  if (run.filename().empty()) run = run.parent_path();  // "DIR/"
  return evaluateRun(run.parent_path(), run, options);
}

std::vector<RunEvaluation> evaluateRunFolders(const std::string& dir, const EvalOptions& options) {
  if (!fs::is_directory(dir)) throw InputError(dir, 0, "results folder not found");
  std::set<fs::path> runs;
  for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied);
       it != fs::recursive_directory_iterator(); ++it) {
    const std::string name = it->path().filename().string();
    if (it->is_regular_file() && (name == "summary.json" || name == "trajectory_tum.txt"))
      runs.insert(it->path().parent_path());
  }
  std::vector<RunEvaluation> out;
  for (const auto& run : runs) out.push_back(evaluateRun(dir, run, options));
  std::sort(out.begin(), out.end(), [](const RunEvaluation& a, const RunEvaluation& b) {
    return std::tie(a.sequence, a.mode, a.folder) < std::tie(b.sequence, b.mode, b.folder);
  });
  return out;
}

namespace {
/// The largest ATE of a run's segments between losses (NaN without any).
double worstSegmentAte(const RunEvaluation& r) {
  return r.segment_ate_m.empty() ? kNaN : *std::max_element(r.segment_ate_m.begin(), r.segment_ate_m.end());
}

/// "ok", or "lost 1.5 s (longest 0.6 s); 3 segments, ATE <= 0.012 m" for a
/// run with losses; frames lost without a word come first.
std::string statusText(const RunEvaluation& r) {
  const std::string unaccounted =
      r.unaccounted_frames.value_or(0) != 0 ? "**" + std::to_string(*r.unaccounted_frames) + " frames unaccounted**" : std::string();
  if (r.lost_intervals == 0) return unaccounted.empty() ? "ok" : unaccounted;
  std::string s = (unaccounted.empty() ? "" : unaccounted + "; ") + "lost " + num(r.lost_s, 1) + " s";
  if (r.lost_intervals > 1) s += " (longest " + num(r.longest_loss_s, 1) + " s)";
  if (!r.segment_ate_m.empty())
    s += "; " + std::to_string(r.segment_ate_m.size()) + (r.segment_ate_m.size() == 1 ? " segment" : " segments") + ", ATE <= " +
         num(worstSegmentAte(r), 3) + " m";
  return s;
}
}  // namespace

std::string runLabel(const RunEvaluation& r) {
  std::string label = r.mode;
  if (r.skip > 0) label += ", skip " + std::to_string(r.skip);
  if (r.skip_offset > 0) label += " from frame " + std::to_string(r.skip_offset);
  return label;
}

void writeReportMarkdown(std::ostream& out, const std::vector<RunEvaluation>& runs, const EvalOptions& options) {
  std::size_t failures = 0;
  for (const auto& r : runs) failures += !r.ok;
  out << "# edgevio evaluation report\n\n"
      << runs.size() << " runs, " << failures << " failed. ATE after " << alignmentName(options.alignment)
      << " alignment; ARE over segments of ";
  if (options.are_segments_m.empty()) {
    for (std::size_t i = 0; i < options.are_segments_percent.size(); ++i)
      out << (i ? ", " : "") << options.are_segments_percent[i] << " %";
    out << " of each trajectory's length";
  } else {
    for (std::size_t i = 0; i < options.are_segments_m.size(); ++i) out << (i ? ", " : "") << options.are_segments_m[i] << " m";
  }
  out << ".\n\n| sequence | mode | status | frames | matched | ATE RMSE [m] | ARE-rot [deg/m] | ARE-trans [m/m] |";
  for (double d : options.rpe_deltas_m) out << " RPE " << d << " m [m] |";
  out << " length [m] | RT factor | peak memory [MB] |\n|---|---|---|---:|---:|---:|---:|---:|";
  for (std::size_t i = 0; i < options.rpe_deltas_m.size(); ++i) out << "---:|";
  out << "---:|---:|---:|\n";
  for (const auto& r : runs) {
    out << "| " << r.sequence << " | " << runLabel(r) << " | ";
    const std::string frames = r.frames < 0 ? "-" : r.frames_to_process < 0 ? std::to_string(r.frames)
                                                     : std::to_string(r.frames) + "/" + std::to_string(r.frames_to_process);
    if (!r.ok) {
      out << "**FAILED**: " << r.failure << " | " << frames << " | - | - | - | - |";
      for (std::size_t i = 0; i < options.rpe_deltas_m.size(); ++i) out << " - |";
      out << " - | " << num(r.realtime_factor, 1) << " | " << num(r.peak_rss_mb, 0) << " |\n";
      continue;
    }
    out << statusText(r) << " | " << frames << " | " << r.result.matched << " | " << num(r.result.ate_rmse_m, 4) << " | "
        << num(r.result.are_rot_deg_per_m, 5) << " | " << num(r.result.are_trans_m_per_m, 5) << " |";
    for (const auto& e : r.result.rpe) out << " " << num(e.trans_rmse_m, 4) << " |";
    out << " " << num(r.result.length_m, 1) << " | " << num(r.realtime_factor, 1) << " | " << num(r.peak_rss_mb, 0) << " |\n";
  }
}

void writeReportCsv(std::ostream& out, const std::vector<RunEvaluation>& runs) {
  out << "sequence,mode,folder,status,failure,matched,align,ate_rmse_m,ate_mean_m,ate_median_m,ate_max_m,"
         "are_rot_deg_per_m,are_trans_m_per_m,rpe_deltas_m,rpe_trans_rmse_m,rpe_rot_rmse_deg,length_m,duration_s,"
         "realtime_factor,skip,skip_offset,peak_rss_mb,latency_p50_ms,latency_p99_ms,lost_intervals,lost_s,segments,segment_ate_max_m,"
         "longest_loss_s,frames,frames_to_process,unaccounted_frames\n";
  for (const auto& r : runs) {
    out << csvField(r.sequence) << "," << csvField(r.mode) << "," << csvField(r.folder) << ","
        << (r.ok ? "ok" : "failed") << "," << csvField(r.failure) << ",";
    if (r.ok) {
      const EvalResult& e = r.result;
      std::string deltas, trans, rot;
      for (std::size_t i = 0; i < e.rpe.size(); ++i) {
        const std::string sep = i ? ";" : "";
        deltas += sep + num(e.rpe[i].delta_m, 3);
        trans += sep + num(e.rpe[i].trans_rmse_m, 6);
        rot += sep + num(e.rpe[i].rot_rmse_deg, 6);
      }
      out << e.matched << "," << alignmentName(e.alignment) << "," << num(e.ate_rmse_m, 6) << ","
          << num(e.ate_mean_m, 6) << "," << num(e.ate_median_m, 6) << "," << num(e.ate_max_m, 6) << ","
          << num(e.are_rot_deg_per_m, 6) << "," << num(e.are_trans_m_per_m, 6) << "," << deltas << "," << trans
          << "," << rot << "," << num(e.length_m, 3) << "," << num(e.duration_s, 3) << ",";
    } else {
      out << ",,,,,,,,,,,,,";
    }
    out << (std::isfinite(r.realtime_factor) ? num(r.realtime_factor, 2) : "") << "," << r.skip << "," << r.skip_offset << ","
        << (std::isfinite(r.peak_rss_mb) ? num(r.peak_rss_mb, 1) : "") << ","
        << (std::isfinite(r.latency_p50_ms) ? num(r.latency_p50_ms, 2) : "") << ","
        << (std::isfinite(r.latency_p99_ms) ? num(r.latency_p99_ms, 2) : "") << "," << r.lost_intervals << "," << num(r.lost_s, 3)
        << "," << r.segment_ate_m.size() << ","
        << (r.segment_ate_m.empty() ? "" : num(worstSegmentAte(r), 6)) << "," << num(r.longest_loss_s, 3) << ","
        << (r.frames < 0 ? "" : std::to_string(r.frames)) << ","
        << (r.frames_to_process < 0 ? "" : std::to_string(r.frames_to_process)) << ","
        << (r.unaccounted_frames ? std::to_string(*r.unaccounted_frames) : "") << "\n";
  }
}

}  // namespace edgevio::eval
