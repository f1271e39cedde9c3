#pragma once
// Batch evaluation of run folders (`edgevio eval --results DIR`).
//
// A run folder is any folder under DIR holding `summary.json` or
// `trajectory_tum.txt` (what `edgevio run --out` writes). Its ground truth is,
// in this order: summary.json's "groundtruth" (a file, relative to the run
// folder or absolute); summary.json's "dataset" (an ASL folder, whose
// mav0/state_groundtruth_estimate0/data.csv is used); or a file named
// groundtruth.csv, groundtruth_tum.txt or groundtruth.txt in the run folder.
// The row's sequence is summary.json's "sequence" (else the folder's path under
// DIR) and its mode is summary.json's "mode". A run whose summary says
// "failed": true, whose trajectory is missing, or that cannot be evaluated is a
// failure row with the reason: never dropped.
#include <iosfwd>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "edgevio/eval/metrics.h"

namespace edgevio::eval {

struct RunEvaluation {
  std::string folder;    ///< relative to DIR
  std::string sequence;
  std::string mode;
  bool ok = false;
  std::string failure;   ///< why, when !ok
  EvalResult result;
  double realtime_factor = 0.0;  ///< from summary.json when present, else NaN
  int skip = 0;                  ///< frames skipped between processed ones (summary.json "skip")
  int skip_offset = 0;           ///< the first frame processed, 0..skip (summary.json "skip_offset")
  double peak_rss_mb = 0.0;      ///< the run's peak resident memory (summary.json "peak_rss_mb"), else NaN
  double latency_p50_ms = 0.0, latency_p99_ms = 0.0;  ///< summary.json "latency_ms" p50 and p99, else NaN
  int lost_intervals = 0;  ///< summary.json "lost_intervals": how many ...
  double lost_s = 0.0;     ///< ... and their total length [s]
  double longest_loss_s = 0.0;  ///< the longest of them: the time to recover [s]
  /// summary.json "frames" (rows of frames.csv) of "frames_to_process" (-1
  /// when absent), and "unaccounted_frames" (frames lost without a word).
  long long frames = -1, frames_to_process = -1;
  std::optional<long long> unaccounted_frames;
  /// With lost intervals: the ATE RMSE of each segment between them, each
  /// aligned alone (segments shorter than kMinSegmentPoses are left out).
  std::vector<double> segment_ate_m;
};

/// A segment between losses needs this many poses to be evaluated: an
/// alignment of fewer fits much of their error away (one second at 20 Hz).
inline constexpr std::size_t kMinSegmentPoses = 20;

/// The estimate's pieces outside the lost intervals, given as (start_s,
/// end_s) after its first pose, in time order; pieces shorter than
/// kMinSegmentPoses are dropped.
std::vector<io::Trajectory> segmentsBetweenLosses(const io::Trajectory& est, const std::vector<std::pair<double, double>>& lost);

/// Finds and evaluates every run folder under `dir`, sorted by sequence, mode, folder.
/// One run folder, as a row of evaluateRunFolders would be.
RunEvaluation evaluateRunFolder(const std::string& run_dir, const EvalOptions& options);

std::vector<RunEvaluation> evaluateRunFolders(const std::string& dir, const EvalOptions& options);

/// A run's row label in the reports: its mode, then ", skip K" and
/// " from frame P" where they are not 0.
std::string runLabel(const RunEvaluation& r);

void writeReportMarkdown(std::ostream& out, const std::vector<RunEvaluation>& runs, const EvalOptions& options);
void writeReportCsv(std::ostream& out, const std::vector<RunEvaluation>& runs);

}  // namespace edgevio::eval
