// The options table of BackLinkOptions (docs/configuration.md is generated from it).
#include "edgevio/loop/back_link_options.h"

namespace edgevio::loop {

EDGEVIO_OPTIONS_TABLE(BackLinkOptions,
    number("keyframes", &S::keyframes, 2, "-",
           "window modes: each new keyframe's points are aligned back into this many keyframes before it", atLeast(0)),
    number("max_disagreement_m", &S::max_disagreement_m, 0.05, "m",
           "a back link must agree with the estimated relative pose within this translation", above(0)),
    number("max_disagreement_deg", &S::max_disagreement_deg, 1.5, "deg", "... and this rotation", above(0)))

}  // namespace edgevio::loop
