#pragma once
// The edgevio configuration: every module's options struct as one section of
// one YAML document (config/euroc.yaml is the documented default, written by
// `edgevio --print-config`). Each option's key, default, unit, meaning and
// valid values are written once, in its module's options table
// (common/options.h); reading, writing, validation and the reference
// docs/configuration.md all come from those tables. Unknown keys, wrong types
// and invalid values are errors naming the file, line and key.
#include <iosfwd>
#include <string>
#include <vector>

#include "edgevio/camera/rectification_options.h"
#include "edgevio/doctor/doctor_options.h"
#include "edgevio/estimator/estimator_options.h"
#include "edgevio/eval/eval_options.h"
#include "edgevio/io/dataset_options.h"
#include "edgevio/loop/back_link_options.h"
#include "edgevio/loop/loop_options.h"
#include "edgevio/sim/sim_options.h"
#include "edgevio/tracking/alignment_options.h"
#include "edgevio/tracking/tracking_options.h"
#include "edgevio/vision/vision_options.h"

namespace YAML {
class Node;
}

namespace edgevio {

struct Config {
  io::DatasetOptions dataset;
  camera::RectificationOptions rectification;
  vision::VisionOptions vision;
  tracking::AlignmentOptions alignment;
  tracking::TrackingOptions tracking;
  estimator::EstimatorOptions estimator;
  loop::BackLinkOptions back_links;
  loop::LoopOptions loop;
  eval::EvalOptions eval;
  sim::SimOptions sim;
  doctor::DoctorOptions doctor;

  /// "" when every option is valid, else the first problem as "section.key: why".
  std::string validate() const;
};

/// Calls f(name, meaning, section) for each section of `config` in file order.
template <class C, class F>
void forEachSection(C& config, F&& f) {
  f("dataset", "dataset input (METHOD.md §1, the driver)", config.dataset);
  f("rectification", "stereo rectification (METHOD.md §3, pre-processing)", config.rectification);
  f("vision", "front-end image processing: pyramid, Canny, stereo depth (METHOD.md §3)", config.vision);
  f("alignment", "edge alignment: Gauss-Newton, robust weights, self check (METHOD.md §3)", config.alignment);
  f("tracking", "keyframe policy, checks against the prediction, static initialisation (METHOD.md §3, §5)", config.tracking);
  f("estimator", "sliding-window estimator: IMU links, external check, two-way marginalisation (METHOD.md §4, §5)",
    config.estimator);
  f("back_links", "links from each new keyframe back into the keyframes before it (not in METHOD.md; window modes)",
    config.back_links);
  f("loop", "local loop closure between keyframes in the window (METHOD.md §6)", config.loop);
  f("eval", "trajectory evaluation: association, alignment, metrics (METHOD.md §8)", config.eval);
  f("sim", "simulator: motion, scene, camera effects, IMU (edgevio simulate)", config.sim);
  f("doctor", "checks of a rig's data before a run: what it reads, when a measurement is a finding (edgevio doctor)",
    config.doctor);
}

/// Reads a config file over the defaults. Keys absent from the file keep their
/// defaults and are listed in `missing_keys` (as "section.key") when given.
Config loadConfig(const std::string& path, std::vector<std::string>* missing_keys = nullptr);

/// Reads a `sim:` section found in another file (a render's
/// simulation.yaml) as a config file's: errors name `path`, the line and the key.
void readSimOptions(const YAML::Node& section, const std::string& path, sim::SimOptions* options);

/// Writes the config as YAML with every key, its unit, meaning and valid values as comments.
void writeConfig(std::ostream& out, const Config& config);

/// Writes the reference of every option as Markdown (docs/configuration.md).
void writeConfigReference(std::ostream& out);

}  // namespace edgevio
