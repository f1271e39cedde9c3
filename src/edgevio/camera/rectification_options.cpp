#include "edgevio/camera/rectification_options.h"

namespace edgevio::camera {

std::string RectificationOptions::validate() const {
  if (!(alpha >= 0.0 && alpha <= 1.0)) return "alpha: must be in [0, 1]";
  return {};
}

}  // namespace edgevio::camera
