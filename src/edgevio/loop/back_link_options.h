#pragma once
#include "edgevio/common/options.h"

namespace edgevio::loop {

/// Back links (config section `back_links`; loop/back_links.h).
struct BackLinkOptions {
  int keyframes;
  double max_disagreement_m, max_disagreement_deg;

  EDGEVIO_OPTIONS(BackLinkOptions)
};

EDGEVIO_OPTIONS_TABLE(BackLinkOptions,
    number("keyframes", &S::keyframes, 2, "-",
           "window modes: each new keyframe's points are aligned back into this many keyframes before it", atLeast(0)),
    number("max_disagreement_m", &S::max_disagreement_m, 0.05, "m",
           "a back link must agree with the estimated relative pose within this translation", above(0)),
    number("max_disagreement_deg", &S::max_disagreement_deg, 1.5, "deg", "... and this rotation", above(0)))

}  // namespace edgevio::loop
