#pragma once
// From scene radiance to an 8-bit camera image (issue #4 camera effects):
//   I(u,v) = clamp(round(255 · gain · V(u,v) · L(u,v) + σ·n(u,v)), 0, 255)
// with exposure gain (auto-exposure drift, lighting changes, left/right
// mismatch folded in by the caller), vignetting V = 1 − k·r² (r = distance to
// the principal point over the half diagonal), and Gaussian read noise n drawn
// from a hash of (key, pixel), so images do not depend on thread scheduling.
#include <opencv2/core.hpp>

#include <cstdint>

#include "edgevio/camera/camera_model.h"

namespace edgevio::sim {

struct SensorEffects {
  double gain = 1.0;
  double vignetting = 0.0;   ///< k in V = 1 − k·r²
  double noise_sigma = 0.0;  ///< read noise [DN]
};

cv::Mat sensorImage(const cv::Mat& radiance, const camera::CameraModel& camera, const SensorEffects& effects,
                    std::uint64_t noise_key);

}  // namespace edgevio::sim
