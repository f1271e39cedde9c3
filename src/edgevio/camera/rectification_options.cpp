// The options table of RectificationOptions (docs/configuration.md is generated from it).
#include "edgevio/camera/rectification_options.h"

namespace edgevio::camera {

EDGEVIO_OPTIONS_TABLE(RectificationOptions,
    number("alpha", &S::alpha, 0.0, "-", "free scaling of stereoRectify: 0 keeps only valid pixels (paper), 1 keeps every pixel",
           closed(0, 1)))

}  // namespace edgevio::camera
