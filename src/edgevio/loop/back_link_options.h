#pragma once
#include "edgevio/common/options.h"

namespace edgevio::loop {

/// Back links (config section `back_links`; loop/back_links.h).
struct BackLinkOptions {
  int keyframes;
  double max_disagreement_m, max_disagreement_deg;

  EDGEVIO_OPTIONS(BackLinkOptions)
};

// BackLinkOptions's keys, defaults, units, meanings and valid values: its table in back_link_options.cpp.

}  // namespace edgevio::loop
