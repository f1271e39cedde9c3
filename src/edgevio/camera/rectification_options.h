#pragma once
#include "edgevio/common/options.h"

namespace edgevio::camera {

/// Stereo rectification (config section `rectification`; METHOD.md §3).
struct RectificationOptions {
  double alpha;

  EDGEVIO_OPTIONS(RectificationOptions)
};

EDGEVIO_OPTIONS_TABLE(RectificationOptions,
    number("alpha", &S::alpha, 0.0, "-", "free scaling of stereoRectify: 0 keeps only valid pixels (paper), 1 keeps every pixel",
           closed(0, 1)))

}  // namespace edgevio::camera
