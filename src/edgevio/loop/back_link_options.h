#pragma once
#include <string>

namespace edgevio::loop {

/// Options of back links (config section `back_links`; see back_links.h).
struct BackLinkOptions {
  int keyframes = 2;                  ///< align each new keyframe back into this many keyframes before it (0: off) [-]
  double max_disagreement_m = 0.05;   ///< a back link against its initial guess (the estimate): translation [m]
  double max_disagreement_deg = 1.5;  ///< ... rotation [deg]

  template <class Visitor>
  void visit(Visitor& v) {
    v("keyframes", keyframes, "-", "window modes: align each new keyframe's points back into this many keyframes before it (0: off)");
    v("max_disagreement_m", max_disagreement_m, "m", "a back link must agree with the estimated relative pose within this translation");
    v("max_disagreement_deg", max_disagreement_deg, "deg", "... and this rotation");
  }
  std::string validate() const {
    if (keyframes < 0) return "keyframes: must be >= 0";
    if (!(max_disagreement_m > 0 && max_disagreement_deg > 0)) return "max_disagreement_*: must be > 0";
    return {};
  }
};

}  // namespace edgevio::loop
