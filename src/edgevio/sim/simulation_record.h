#pragma once
// A render folder's simulation.yaml (written by `edgevio simulate`) read
// back: the request and the sim options it was made with, from which
// simulatedWorld brings back its motion and scene. Its `sim:` block is read
// as a config file's section (config/config.h).
#include <string>

#include "edgevio/sim/sim_options.h"
#include "edgevio/sim/simulator.h"

namespace edgevio::sim {

struct SimulationRecord {
  SimRequest request;  ///< out_dir: the folder
  SimOptions options;
};

/// Throws InputError naming the file and line for a missing or bad record.
SimulationRecord loadSimulationRecord(const std::string& folder);

}  // namespace edgevio::sim
