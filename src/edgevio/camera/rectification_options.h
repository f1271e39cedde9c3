#pragma once
#include <string>

namespace edgevio::camera {

/// Options of stereo rectification (config section `rectification`; METHOD.md §3).
struct RectificationOptions {
  /// Free-scaling parameter of stereoRectify: 0 keeps only valid pixels, 1 keeps all source pixels. [-]
  double alpha = 0.0;

  template <class Visitor>
  void visit(Visitor& v) {
    v("alpha", alpha, "-", "stereo rectification free scaling: 0 = only valid pixels (paper), 1 = all pixels");
  }
  std::string validate() const;
};

}  // namespace edgevio::camera
