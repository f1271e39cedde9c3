#pragma once
// The subcommands of the `edgevio` program. apps/edgevio_main.cpp only parses
// the command line and calls these; each returns the process exit status:
//   0 success, 1 bad input or failed run (message on err), 2 not implemented.
#include <iosfwd>
#include <limits>
#include <string>
#include <vector>

#include "edgevio/eval/eval_options.h"
#include "edgevio/io/sequence.h"

namespace edgevio::cli {

constexpr int kExitOk = 0;
constexpr int kExitError = 1;

struct InfoArgs {
  io::SequenceSource source;
  std::string config;  ///< optional config file
};
/// `edgevio info DATA`: one JSON object describing an ASL folder or a bag.
int info(const InfoArgs& args, std::ostream& out, std::ostream& err);

struct DoctorArgs {
  io::SequenceSource source;
  std::string config;              ///< optional config file
  std::string format = "text";     ///< text | json
  std::string html = "doctor.html";  ///< the page with the plots (empty: none)
};
/// `edgevio doctor DATA`: what is wrong with a rig's data, before any run.
int doctor(const DoctorArgs& args, std::ostream& out, std::ostream& err);

struct EvalArgs {
  std::string gt, est, results_dir, config;
  std::string align;                  ///< empty: from config
  std::vector<double> deltas_m;       ///< empty: from config
  std::string segments;               ///< "10%,20%" or "1m,5m"; empty: from config
  std::string format = "table";       ///< json | table
  std::string plot;                   ///< SVG path, optional
};
/// `edgevio eval`: trajectory metrics (issue #3).
int eval(const EvalArgs& args, std::ostream& out, std::ostream& err);

struct SimulateArgs {
  std::string out, trajectory, scenario, imu = "synth", noise = "on", calib, config;
  std::vector<std::string> faults;  ///< --fault specs (sim/faults.h)
  double start_s = 0.0;
  double duration_s = -1.0;  ///< < 0: default
  unsigned long long seed = 1;
  double blur_ms = 0.0;
  bool exposure_changes = false;
  double drop_rate = 0.0;
  int skip = 0;
  double vignetting = -1.0, stereo_mismatch = -1.0;  ///< < 0: from config
  double imu_time_offset_ms = std::numeric_limits<double>::quiet_NaN();  ///< NaN: from config
};
/// `edgevio simulate`: a synthetic EuRoC ASL folder (issue #4).
int simulate(const SimulateArgs& args, std::ostream& out, std::ostream& err);

struct RunArgs {
  io::SequenceSource source;
  std::string out, mode = "edge+imu+loop", config;  ///< default: the full system
  int skip = 0, skip_offset = 0;
  bool realtime = false;
  int pictures_every = 10;
  std::string mcap;    ///< an MCAP recording to write (empty: none)
  int view_port = -1;  ///< serve the live viewer on this port (0: any free one; -1: no viewer)
};
/// `edgevio run`: estimate a trajectory (issues #5-#8).
int run(const RunArgs& args, std::ostream& out, std::ostream& err);

struct ConvertArgs {
  io::SequenceSource source;
  std::string out, compression = "none", images = "raw";
};
/// `edgevio convert DATA OUT.bag`: any sequence edgevio reads as a ROS 1 bag,
/// with Kalibr's calibration files beside it.
int convert(const ConvertArgs& args, std::ostream& out, std::ostream& err);

struct DemoArgs {
  std::string out = "out/demo";
  double duration_s = 30.0;
  bool fresh = false;
};
/// `edgevio demo`: simulate, estimate, evaluate, print the table.
int demo(const DemoArgs& args, std::ostream& out, std::ostream& err);

struct BenchArgs {
  std::string matrix, out;
  int jobs = 1;
  bool emit_jobs = false;
};
/// `edgevio bench MATRIX.yaml --out DIR [--jobs N] [--emit-jobs]` (issue #8).
int bench(const BenchArgs& args, std::ostream& out, std::ostream& err);

struct ViewArgs {
  std::string run_dir, out;  ///< out empty: RUN_DIR/view.html
};
/// `edgevio view RUN_DIR`: the run as one self-contained HTML page.
int view(const ViewArgs& args, std::ostream& out, std::ostream& err);

/// `edgevio eval --results DIR`: evaluates every run folder, writes DIR/report.md
/// and DIR/report.csv, prints the markdown table.
int evalResults(const std::string& dir, const eval::EvalOptions& options, std::ostream& out, std::ostream& err);


}  // namespace edgevio::cli
