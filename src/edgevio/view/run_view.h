#pragma once
// `edgevio view RUN_DIR`: a finished run folder (pipeline/run_writer.h) as
// the viewer's page (view/page.h): frames.csv, the estimate against its
// ground truth (found as `edgevio eval --results` finds it, aligned as the
// config's eval section says), the ATE over time, the component times and
// every alignment picture the run kept.
#include <string>
#include <vector>

#include "edgevio/eval/eval_options.h"

namespace edgevio::view {

/// The run data of the page (see viewerPage). Throws InputError when the
/// folder has no frames.csv or a file of it cannot be read; a run without
/// ground truth gets no ATE, and `notes` says why.
std::string runViewJson(const std::string& run_dir, const eval::EvalOptions& options, std::vector<std::string>* notes);

/// Writes the page to `out_file` (throws InputError when it cannot).
void writeRunView(const std::string& run_dir, const std::string& out_file, const eval::EvalOptions& options,
                  std::vector<std::string>* notes);

}  // namespace edgevio::view
