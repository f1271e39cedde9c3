#include <filesystem>
#include <fstream>
#include <ostream>

#include "edgevio/cli/commands.h"
#include "edgevio/cli/progress.h"
#include "edgevio/common/error.h"
#include "edgevio/config/config.h"
#include "edgevio/eval/batch.h"
#include "edgevio/eval/metrics.h"
#include "edgevio/eval/report.h"
#include "edgevio/eval/svg_plot.h"
#include "edgevio/pipeline/run.h"
#include "edgevio/sim/simulator.h"
#include "edgevio/view/run_view.h"

namespace edgevio::cli {

namespace fs = std::filesystem;

int demo(const DemoArgs& a, std::ostream& out, std::ostream& err) {
  try {
    const Config config;
    const fs::path root(a.out);
    const pipeline::Mode full_system;
    const std::string mode = pipeline::modeName(full_system);
    const fs::path data = root / "data", run = root / ("run-" + mode);
    // 1. Simulate (once: an existing folder from the same request is reused).
    sim::SimRequest r;
    r.out_dir = data.string();
    r.scenario = "aggressive";
    r.duration_s = a.duration_s;
    r.seed = 1;
    if (!fs::exists(data / "mav0" / "state_groundtruth_estimate0" / "data.csv") || a.fresh) {
      out << "[1/3] simulating " << a.duration_s << " s of the aggressive scenario into " << data.string() << "\n";
      Progress p("stereo frames rendered", Progress::stderrIsTerminal());
      sim::simulate(r, config.sim, [&](std::size_t d, std::size_t t) { p.update(d, t); });
    } else {
      out << "[1/3] reusing the simulated sequence in " << data.string() << " (--fresh to render it again)\n";
    }
    // 2. Estimate.
    out << "[2/3] running the full system (" << mode << ")\n";
    Progress p("frames", Progress::stderrIsTerminal());
    pipeline::RunObserver observer;
    observer.progress = [&](std::size_t d, std::size_t t, double q) { p.update(d, t, q); };
    const pipeline::RunSummary s = pipeline::run({data.string(), run.string(), full_system}, config, observer);
    // 3. Evaluate.
    out << "[3/3] evaluating against the ground truth\n\n";
    const eval::EvalResult e =
        eval::evaluate(io::readTrajectory((data / "mav0" / "state_groundtruth_estimate0" / "data.csv").string()),
                       io::readTrajectory((run / "trajectory_tum.txt").string()), config.eval);
    eval::writeTable(out, e);
    eval::writeSvgPlot((run / "eval.svg").string(), e, "edgevio demo: aggressive, " + mode);
    {
      std::ofstream md(root / "report.md"), csv(root / "report.csv");
      const auto runs = eval::evaluateRunFolders(root.string(), config.eval);
      eval::writeReportMarkdown(md, runs, config.eval);
      eval::writeReportCsv(csv, runs);
    }
    std::vector<std::string> notes;
    view::writeRunView(run.string(), (run / "view.html").string(), config.eval, &notes);
    out << "\n" << s.frames << " frames, " << s.keyframes << " keyframes, " << s.loop_closures << " loop closures, real-time factor "
        << s.realtime_factor << (s.lost_intervals.empty() ? std::string() : "; " + s.lossText())
        << (s.failed ? "; RUN FAILED: " + s.failure : std::string()) << "\n"
        << "trajectory: " << (run / "trajectory_tum.txt").string() << "\n"
        << "plot:       " << (run / "eval.svg").string() << "\n"
        << "viewer:     " << (run / "view.html").string() << " (open it in a browser)\n"
        << "report:     " << (root / "report.md").string() << "\n";
    return s.failed ? kExitError : kExitOk;
  } catch (const InputError& e) {
    err << "error: " << e.what() << "\n";
    return kExitError;
  }
}

}  // namespace edgevio::cli
