// edgevio: the command-line program. Parsing only; the work is in the library
// (src/edgevio/cli/commands.h).
#include <CLI/CLI.hpp>

#include <iostream>

#include "edgevio/cli/commands.h"
#include "edgevio/common/process_memory.h"
#include "edgevio/config/config.h"
#include "edgevio/pipeline/run_writer.h"
#include "edgevio/sim/faults.h"

int main(int argc, char** argv) {
  using namespace edgevio;
  keepFreedMemory();
  CLI::App app{"edgevio " EDGEVIO_VERSION
               ": edge-alignment stereo visual-inertial odometry for aggressive motion"};
  app.require_subcommand(0, 1);
  app.set_version_flag("--version", EDGEVIO_VERSION);
  bool print_config = false, print_config_reference = false, print_outputs_reference = false;
  app.add_flag("--print-config", print_config, "Print the default configuration (every parameter, documented) and exit");
  app.add_flag("--print-config-reference", print_config_reference, "Print the configuration reference (Markdown) and exit");
  app.add_flag("--print-outputs-reference", print_outputs_reference, "Print the reference of a run folder's files (Markdown) and exit");

  // The options of a ROS bag input, for every subcommand that reads one.
  // The dataset to read (first positional) and, for a bag, its calibration and topics.
  const auto sequenceOptions = [](CLI::App* cmd, io::SequenceSource* source) {
    io::BagTopics* topics = &source->topics;
    cmd->add_option("dataset", source->path, "ASL folder (holding mav0/) or ROS 1 bag")->required();
    cmd->add_option("--calib", source->calib, "A bag's calibration: Kalibr camchain-imucam.yaml or an ASL folder (default: beside the bag)");
    cmd->add_option("--cam0-topic", topics->cam0, "A bag's left image topic (default: found by type and name)");
    cmd->add_option("--cam1-topic", topics->cam1, "A bag's right image topic");
    cmd->add_option("--imu-topic", topics->imu, "A bag's IMU topic (default: the one sensor_msgs/Imu topic)");
    cmd->add_option("--gt-topic", topics->groundtruth, "A bag's ground-truth topic (PoseStamped, TransformStamped or Odometry)");
  };

  cli::InfoArgs info;
  auto* info_cmd = app.add_subcommand("info", "Describe a dataset (ASL folder or ROS bag) as one JSON object");
  sequenceOptions(info_cmd, &info.source);
  info_cmd->add_option("--config", info.config, "Config file (YAML; default: built-in defaults)");

  cli::DoctorArgs doc;
  auto* doctor_cmd = app.add_subcommand("doctor", "Check a dataset's calibration, clocks, IMU and images before a run");
  sequenceOptions(doctor_cmd, &doc.source);
  doctor_cmd->add_option("--config", doc.config, "Config file (YAML; section doctor: what it reads, its thresholds)");
  doctor_cmd->add_option("--format", doc.format, "Output format")->check(CLI::IsMember({"text", "json"}));
  doctor_cmd->add_option("--html", doc.html, "The page with the plots of the evidence (empty: none)");

  cli::RunArgs run;
  auto* run_cmd = app.add_subcommand("run", "Estimate a trajectory from a dataset");
  sequenceOptions(run_cmd, &run.source);
  run_cmd->add_option("--out", run.out, "Output folder")->required();
  run_cmd->add_option("--mode", run.mode, "edge+imu+loop (default, the full system) | edge+imu | edge+loop | edge-only");
  run_cmd->add_option("--config", run.config, "Config file (YAML)");
  run_cmd->add_option("--skip", run.skip, "Keep every (K+1)-th stereo frame (the IMU is untouched)");
  run_cmd->add_option("--skip-offset", run.skip_offset,
                      "With --skip K, start at frame P (0..K): the K+1 offsets together use every frame once (default 0)");
  run_cmd->add_flag("--realtime", run.realtime, "Play the dataset at sensor rate, dropping frames when behind");
  run_cmd->add_option("--pictures-every", run.pictures_every,
                      "Keep the alignment picture of every Nth frame besides the eventful ones (default 10; 0: none)");
  run_cmd->add_option("--view", run.view_port, "Serve the live viewer on 127.0.0.1:PORT while the run goes (default 8700; 0: any free port)")
      ->expected(0, 1)
      ->default_str("8700");
  run_cmd->add_option("--mcap", run.mcap, "Also write an MCAP recording for Foxglove or Lichtblick (poses, paths, pictures, events)");

  cli::ConvertArgs conv;
  auto* convert_cmd = app.add_subcommand("convert", "Write a dataset (ASL folder or bag) as a ROS 1 bag, Kalibr calibration beside it");
  sequenceOptions(convert_cmd, &conv.source);
  convert_cmd->add_option("out", conv.out, "The bag to write (OUT.bag)")->required();
  convert_cmd->add_option("--compression", conv.compression, "Chunk compression: none (default) | bz2 | lz4");
  convert_cmd->add_option("--images", conv.images, "raw (sensor_msgs/Image, default) | png (sensor_msgs/CompressedImage)");

  cli::EvalArgs ev;
  auto* eval_cmd = app.add_subcommand("eval", "Evaluate an estimated trajectory against ground truth (ATE, RPE, ARE)");
  eval_cmd->add_option("--gt", ev.gt, "Ground-truth trajectory (TUM, EuRoC CSV, or a ROS bag's pose topic)");
  eval_cmd->add_option("--est", ev.est, "Estimated trajectory (TUM or EuRoC CSV)");
  eval_cmd->add_option("--results", ev.results_dir, "Evaluate every run folder under DIR; write report.md and report.csv");
  eval_cmd->add_option("--align", ev.align, "Alignment: se3 | sim3 | posyaw | none (default: config, se3)")
      ->check(CLI::IsMember({"se3", "sim3", "posyaw", "none"}));
  eval_cmd->add_option("--delta-m", ev.deltas_m, "RPE travelled-distance delta in metres (repeatable)");
  eval_cmd->add_option("--segments", ev.segments, "ARE segment lengths: 10%,20%,... or 1m,5m,...");
  eval_cmd->add_option("--format", ev.format, "Output format")->check(CLI::IsMember({"json", "table"}));
  eval_cmd->add_option("--plot", ev.plot, "Write an SVG plot (top view and ATE over time)");
  eval_cmd->add_option("--config", ev.config, "Config file (YAML)");

  cli::SimulateArgs sim;
  auto* sim_cmd = app.add_subcommand("simulate", "Render a synthetic stereo+IMU sequence as an EuRoC ASL folder");
  sim_cmd->add_option("--out", sim.out, "Output folder (mav0/ is written inside)")->required();
  auto* traj_opt = sim_cmd->add_option("--trajectory", sim.trajectory, "Trajectory to follow (TUM, EuRoC ground truth, or a ROS bag's pose topic)");
  auto* scen_opt = sim_cmd->add_option("--scenario", sim.scenario, "Built-in motion")
                       ->check(CLI::IsMember({"hover", "figure8", "aggressive", "throw"}));
  traj_opt->excludes(scen_opt);
  sim_cmd->add_option("--start", sim.start_s, "Start, seconds after the trajectory's first pose");
  sim_cmd->add_option("--duration", sim.duration_s, "Length in seconds (default: whole file, or sim.scenario_duration_s)");
  sim_cmd->add_option("--seed", sim.seed, "Seed of everything random (scene, noise, drops)");
  sim_cmd->add_option("--imu", sim.imu, "synth (from the trajectory), or a real imu0 data.csv or ROS bag to replay");
  sim_cmd->add_option("--noise", sim.noise, "on|off: IMU noise and biases, image sensor noise")
      ->check(CLI::IsMember({"on", "off"}));
  sim_cmd->add_option("--blur-ms", sim.blur_ms, "Exposure time for motion blur in ms (0: none)");
  sim_cmd->add_flag("--exposure-changes", sim.exposure_changes, "Auto-exposure drift and sudden lighting changes");
  sim_cmd->add_option("--drop-rate", sim.drop_rate, "Probability that a cam1 frame is dropped");
  sim_cmd->add_option("--fault", sim.faults,
                      "A sensor fault, repeatable: KIND[:at=S,for=S,every=S,size=X], times in seconds after the first frame; KIND: " +
                          options::choiceList(sim::kFaultKindChoices));
  sim_cmd->add_option("--skip", sim.skip, "Keep every (K+1)-th frame");
  sim_cmd->add_option("--calib", sim.calib, "Calibration: ASL folder or Kalibr camchain YAML (default: EuRoC)");
  sim_cmd->add_option("--vignetting", sim.vignetting, "Vignetting strength k (default: config sim.vignetting)");
  sim_cmd->add_option("--stereo-mismatch", sim.stereo_mismatch, "Right/left gain mismatch (default: config)");
  sim_cmd->add_option("--imu-time-offset", sim.imu_time_offset_ms,
                      "IMU clock minus camera clock in ms: the IMU's stamps are late by this (default: config)");
  sim_cmd->add_option("--config", sim.config, "Config file (YAML)");
  cli::BenchArgs bench;
  auto* bench_cmd = app.add_subcommand("bench", "Run a benchmark matrix of sequences x modes x skips");
  bench_cmd->add_option("matrix", bench.matrix, "Matrix YAML (sequences, modes, skips, config)")->required();
  bench_cmd->add_option("--out", bench.out, "Output folder (data/, runs/, report.md, report.csv)")->required();
  bench_cmd->add_option("--jobs", bench.jobs, "Runs in parallel on this machine");
  bench_cmd->add_flag("--emit-jobs", bench.emit_jobs, "Print one self-contained shell command per run instead");

  cli::ViewArgs view;
  auto* view_cmd = app.add_subcommand("view", "Write a run folder as one self-contained HTML page (RUN_DIR/view.html)");
  view_cmd->add_option("run", view.run_dir, "A run folder (edgevio run --out)")->required();
  view_cmd->add_option("--out", view.out, "The page to write (default: RUN_DIR/view.html)");

  cli::DemoArgs demo;
  auto* demo_cmd = app.add_subcommand("demo", "Simulate, estimate and evaluate a default sequence");
  demo_cmd->add_option("--out", demo.out, "Output folder");
  demo_cmd->add_option("--duration", demo.duration_s, "Length of the simulated sequence [s]");
  demo_cmd->add_flag("--fresh", demo.fresh, "Render the sequence again even if it exists");

  CLI11_PARSE(app, argc, argv);

  if (print_config) {
    writeConfig(std::cout, Config{});
    return cli::kExitOk;
  }
  if (print_config_reference) {
    writeConfigReference(std::cout);
    return cli::kExitOk;
  }
  if (print_outputs_reference) {
    pipeline::writeOutputsReference(std::cout);
    return cli::kExitOk;
  }

  if (*info_cmd) return cli::info(info, std::cout, std::cerr);
  if (*doctor_cmd) return cli::doctor(doc, std::cout, std::cerr);
  if (*eval_cmd) return cli::eval(ev, std::cout, std::cerr);
  if (*run_cmd) return cli::run(run, std::cout, std::cerr);
  if (*convert_cmd) return cli::convert(conv, std::cout, std::cerr);
  if (*sim_cmd) return cli::simulate(sim, std::cout, std::cerr);
  if (*bench_cmd) return cli::bench(bench, std::cout, std::cerr);
  if (*demo_cmd) return cli::demo(demo, std::cout, std::cerr);
  if (*view_cmd) return cli::view(view, std::cout, std::cerr);
  std::cerr << app.help();
  return cli::kExitError;
}
