#pragma once
// The edgevio configuration: every parameter of every module, each with a
// default, a unit and a one-line meaning, written once in its module's
// Options::visit(). This file combines them into one YAML document
// (config/euroc.yaml is the documented default) and reads it back; unknown keys,
// wrong types and invalid values are errors naming the file, line and key.
#include <iosfwd>
#include <string>
#include <vector>

#include "edgevio/camera/rectification_options.h"
#include "edgevio/estimator/estimator_options.h"
#include "edgevio/eval/eval_options.h"
#include "edgevio/io/dataset_options.h"
#include "edgevio/loop/back_link_options.h"
#include "edgevio/loop/loop_options.h"
#include "edgevio/sim/sim_options.h"
#include "edgevio/tracking/alignment_options.h"
#include "edgevio/tracking/tracking_options.h"
#include "edgevio/vision/vision_options.h"

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

  template <class Visitor>
  void visitSections(Visitor& v) {
    v("dataset", dataset, "EuRoC/ASL dataset input (METHOD.md §1 driver)");
    v("rectification", rectification, "stereo rectification (METHOD.md §3 pre-processing)");
    v("vision", vision, "front-end image processing: pyramid, Canny, stereo depth (METHOD.md §3)");
    v("alignment", alignment, "edge alignment: Gauss-Newton, robust weights, self check (METHOD.md §3)");
    v("tracking", tracking, "keyframe policy, initial guess, static initialisation (METHOD.md §3, §5)");
    v("estimator", estimator, "sliding-window estimator: IMU links, external check, two-way marginalisation (METHOD.md §4, §5)");
    v("back_links", back_links, "links from each new keyframe back into the keyframes before it (not in METHOD.md; window modes)");
    v("loop", loop, "local loop closure between keyframes in the window (METHOD.md §6)");
    v("eval", eval, "trajectory evaluation: association, alignment, metrics (METHOD.md §8)");
    v("sim", sim, "simulator: motion, scene, camera effects, IMU (edgevio simulate)");
  }
  /// Empty when every section is valid, else the first problem, prefixed by its section.
  std::string validate() const;
};

/// Reads a config file over the defaults. Keys absent from the file keep their
/// defaults and are listed in `missing_keys` (as "section.key") when given.
Config loadConfig(const std::string& path, std::vector<std::string>* missing_keys = nullptr);

/// Writes the config as YAML with every key, its unit and meaning as comments.
void writeConfig(std::ostream& out, const Config& config);

}  // namespace edgevio
