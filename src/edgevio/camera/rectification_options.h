#pragma once
#include "edgevio/common/options.h"

namespace edgevio::camera {

/// Stereo rectification (config section `rectification`; METHOD.md §3).
struct RectificationOptions {
  double alpha;

  EDGEVIO_OPTIONS(RectificationOptions)
};

// RectificationOptions's keys, defaults, units, meanings and valid values: its table in rectification_options.cpp.

}  // namespace edgevio::camera
