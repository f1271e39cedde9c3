#pragma once
// A render folder's simulation.yaml (written by `edgevio simulate`) read
// back: the request and the sim options it was made with, from which
// sim::simulatedWorld brings back its motion and scene. Defined beside the
// config reader (config.cpp), whose section parsing reads its `sim:` block.
#include <string>

#include "edgevio/sim/sim_options.h"
#include "edgevio/sim/simulator.h"

namespace edgevio {

struct SimulationRecord {
  sim::SimRequest request;  ///< out_dir: the folder
  sim::SimOptions options;
};

/// Throws InputError naming the file and line for a missing or bad record.
SimulationRecord loadSimulationRecord(const std::string& folder);

}  // namespace edgevio
