#pragma once
#include "edgevio/common/options.h"

namespace edgevio::camera {

/// Stereo rectification (config section `rectification`; METHOD.md §3).
struct RectificationOptions {
  double alpha;

  RectificationOptions() { options::setDefaults(*this); }
  static const options::Table<RectificationOptions>& table();
};

inline const options::Table<RectificationOptions>& RectificationOptions::table() {
  using S = RectificationOptions;
  using namespace options;
  static const Table<S> t{{
      number("alpha", &S::alpha, 0.0, "-", "free scaling of stereoRectify: 0 keeps only valid pixels (paper), 1 keeps every pixel",
             closed(0, 1)),
  }};
  return t;
}

}  // namespace edgevio::camera
