#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/cli/flags.h"
#include "edgevio/common/error.h"
#include "edgevio/common/table_reader.h"
#include "edgevio/config/config.h"
#include "edgevio/eval/metrics.h"
#include "edgevio/eval/batch.h"
#include "edgevio/eval/report.h"
#include "edgevio/eval/svg_plot.h"

#include <fstream>

namespace edgevio::cli {

namespace {
/// "10%,20%" → percentages; "1m,5m" → metres. Mixed units are an error.
void parseSegments(const std::string& text, eval::EvalOptions* options) {
  std::vector<double> percent, metres;
  std::size_t start = 0;
  while (start <= text.size()) {
    const std::size_t comma = text.find(',', start);
    std::string item = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    double v = 0.0;
    if (!item.empty() && item.back() == '%' && parseFiniteDouble(item.substr(0, item.size() - 1), &v) && v > 0) {
      percent.push_back(v);
    } else if (!item.empty() && item.back() == 'm' && parseFiniteDouble(item.substr(0, item.size() - 1), &v) && v > 0) {
      metres.push_back(v);
    } else {
      throw InputError("--segments: '" + item + "' is not a length like 10% or 5m");
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  if (!percent.empty() && !metres.empty()) throw InputError("--segments: use either percentages or metres, not both");
  options->are_segments_percent = percent;
  options->are_segments_m = metres;
}
}  // namespace

int evalResults(const std::string& dir, const eval::EvalOptions& options, std::ostream& out, std::ostream& err) {
  const std::vector<eval::RunEvaluation> runs = eval::evaluateRunFolders(dir, options);
  if (runs.empty()) {
    err << "error: " << dir << ": no run folders found (folders holding summary.json or trajectory_tum.txt)\n";
    return kExitError;
  }
  const std::string md = dir + "/report.md", csv = dir + "/report.csv";
  std::ofstream fmd(md), fcsv(csv);
  if (!fmd || !fcsv) throw InputError(dir, 0, "cannot write report.md / report.csv (is the folder writable?)");
  eval::writeReportMarkdown(fmd, runs, options);
  eval::writeReportCsv(fcsv, runs);
  eval::writeReportMarkdown(out, runs, options);
  out << "\nreport written to " << md << " and " << csv << "\n";
  return kExitOk;
}

int eval(const EvalArgs& args, std::ostream& out, std::ostream& err) {
  try {
    Config config = args.config.empty() ? Config{} : loadConfig(args.config);
    eval::EvalOptions& options = config.eval;
    if (!args.align.empty()) parseFlagChoice("--align", args.align, eval::kAlignmentChoices, &options.alignment);
    if (!args.deltas_m.empty()) options.rpe_deltas_m = args.deltas_m;
    if (!args.segments.empty()) parseSegments(args.segments, &options);
    const std::string invalid = options::validate(options);
    if (!invalid.empty()) throw InputError("invalid evaluation option: " + invalid);

    if (!args.results_dir.empty()) return evalResults(args.results_dir, options, out, err);
    if (args.gt.empty() || args.est.empty())
      throw InputError("eval needs --gt FILE and --est FILE (or --results DIR)");

    const io::Trajectory gt = io::readTrajectory(args.gt);
    const io::Trajectory est = io::readTrajectory(args.est);
    eval::EvalResult result;
    try {
      result = eval::evaluate(gt, est, options);
    } catch (const InputError& e) {
      throw InputError("evaluating " + args.est + " against " + args.gt + ": " + e.what());
    }
    if (args.format == "json") eval::writeJson(out, result);
    else eval::writeTable(out, result);
    if (!args.plot.empty()) {
      eval::writeSvgPlot(args.plot, result, args.est);
      if (args.format != "json") out << "plot written to " << args.plot << "\n";
    }
    return kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
