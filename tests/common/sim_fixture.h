#pragma once
// Simulator inputs shared by the simulator's unit and end-to-end tests.
#include <cstdint>
#include <string>
#include <vector>

#include "edgevio/camera/calibration.h"
#include "edgevio/io/calibration_io.h"
#include "edgevio/sim/scene.h"
#include "edgevio/sim/simulator.h"
#include "edgevio/sim/trajectory_source.h"

namespace edgevio::test {

/// Default options with smaller textures: a quicker setup; rendering itself is unchanged.
inline sim::SimOptions fastSimOptions() {
  sim::SimOptions o;
  o.scene.texture_log2_size = 8;
  return o;
}

/// A built-in scenario's span [start_s, start_s + duration_s], written to out.
inline sim::SimRequest scenarioRequest(const std::string& out, const std::string& scenario, double start_s, double duration_s,
                                       std::uint64_t seed) {
  sim::SimRequest r;
  r.out_dir = out;
  r.scenario = scenario;
  r.start_s = start_s;
  r.duration_s = duration_s;
  r.seed = seed;
  return r;
}

/// 0.6 s of the figure8 scenario from 1.5 s, seed 3.
inline sim::SimRequest shortScenario(const std::string& out) { return scenarioRequest(out, "figure8", 1.5, 0.6, 3); }

/// A span of a real EuRoC recording: its ground truth, its IMU log replayed.
inline sim::SimRequest replayRequest(const std::string& euroc_dir, const std::string& out, double start_s, double duration_s) {
  sim::SimRequest r;
  r.out_dir = out;
  r.trajectory_file = euroc_dir + "/groundtruth.csv";
  r.imu = euroc_dir + "/imu0.csv";
  r.start_s = start_s;
  r.duration_s = duration_s;
  return r;
}

/// The EuRoC rig in a room around 14 s of the figure8 scenario (scene seed 5).
struct FigureEightWorld {
  camera::StereoRig rig = io::eurocDefaultRig();
  io::Trajectory samples = sim::scenarioSamples("figure8", 14.0, 1.0, rig.T_b_c[0]);
  std::vector<Vec3> path;
  sim::Scene scene;
  FigureEightWorld() {
    for (const auto& s : samples) path.push_back(s.T_w_b.translation());
    sim::SceneOptions o;
    o.texture_log2_size = 9;
    scene = sim::buildScene(path, o, 5);
  }
  static const FigureEightWorld& get() {
    static const FigureEightWorld w;
    return w;
  }
};

/// The run tests' render: 4 s of the figure8 scenario, seed 9, textures of
/// 512 px, with `faults`, written to out_dir; returns out_dir.
inline std::string renderFigure8(const std::string& out_dir, const std::vector<sim::Fault>& faults = {}) {
  sim::SimRequest r = scenarioRequest(out_dir, "figure8", 0.0, 4.0, 9);
  r.faults = faults;
  sim::SimOptions o;
  o.scene.texture_log2_size = 9;
  sim::simulate(r, o);
  return out_dir;
}

}  // namespace edgevio::test
