#pragma once
// `edgevio simulate`: renders a stereo+IMU sequence along a trajectory file or
// a scenario and writes a complete EuRoC ASL folder (issue #4):
//   mav0/cam{0,1}/{data.csv, data/<t>.png, sensor.yaml}, mav0/imu0/{data.csv,
//   sensor.yaml}, mav0/state_groundtruth_estimate0/data.csv (p, q, v, true
//   biases at the IMU rate), and simulation.yaml (the request and config used).
// Faults (sim/faults.h) change what the sensor files report, never the
// ground truth.
// Deterministic: the same request, config and seed give byte-identical files.
#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "edgevio/camera/calibration.h"
#include "edgevio/io/trajectory_io.h"
#include "edgevio/sim/faults.h"
#include "edgevio/sim/scene.h"
#include "edgevio/sim/sim_options.h"
#include "edgevio/sim/spline_trajectory.h"

namespace edgevio::sim {

struct SimRequest {
  std::string out_dir;
  std::string trajectory_file;  ///< either this ...
  std::string scenario;         ///< ... or this
  double start_s = 0.0;         ///< offset from the trajectory's first pose [s]
  double duration_s = std::numeric_limits<double>::quiet_NaN();  ///< NaN: to the end (file) or config (scenario)
  std::uint64_t seed = 1;
  std::string imu = "synth";    ///< "synth" or a real EuRoC imu0 data.csv to replay
  bool noise = true;            ///< IMU noise and biases, image sensor noise
  double blur_ms = 0.0;         ///< exposure time for motion blur; 0 = none
  bool exposure_changes = false;
  double drop_rate = 0.0;       ///< probability that a cam1 frame is dropped
  int skip = 0;                 ///< keep every (skip+1)-th frame
  std::string calib;            ///< calibration (ASL folder or Kalibr YAML); empty: EuRoC
  std::vector<Fault> faults;    ///< what the sensors report wrong (sim/faults.h)
};

struct SimSummary {
  std::size_t frames = 0;         ///< stereo instants rendered
  std::size_t dropped_cam1 = 0;
  std::size_t fault_dropped[2] = {0, 0};  ///< images a drop_left / drop_right fault removed
  std::size_t imu_samples = 0;
  int position_steps_removed = 0;  ///< removePositionSteps on the trajectory file (sim.trajectory_max_accel_mps2)
  double duration_s = 0.0;
  double knot_dt_s = 0.0;          ///< spline knot spacing used: sim.knot_dt_s or the file's sample spacing [s]
  double wall_s = 0.0;
  double setup_s = 0.0;           ///< motion, scene (textures), IMU, ray tables: before the first frame
  double render_s = 0.0;          ///< time spent ray casting
  double write_s = 0.0;           ///< time spent encoding and writing images
};

/// What a simulation's images are rendered from: the rig, the motion and the
/// scene. The same request and options give the same world, so a render
/// folder's simulation.yaml (sim/simulation_record.h) brings it back, to
/// render what the files do not hold, such as the true depth at any pose.
struct SimulatedWorld {
  camera::StereoRig rig;
  io::Trajectory samples;  ///< the trajectory file's (position steps removed) or the scenario's
  std::string source;      ///< the file, or "scenario NAME", for messages
  int position_steps_removed = 0;
  std::int64_t begin_ns = 0, end_ns = 0;  ///< the rendered span
  double knot_dt_s = 0.0;
  SplineTrajectory motion;  ///< the body's true pose at any time of the span
  Scene scene;
};

/// Throws InputError for bad input (files, spans, scene), naming the file.
SimulatedWorld simulatedWorld(const SimRequest& request, const SimOptions& options);

/// Progress callback: (frames done, frames total).
using SimProgress = std::function<void(std::size_t, std::size_t)>;

/// Runs the simulation; throws InputError for bad input (files, spans, scene).
SimSummary simulate(const SimRequest& request, const SimOptions& options, const SimProgress& progress = {});

}  // namespace edgevio::sim
