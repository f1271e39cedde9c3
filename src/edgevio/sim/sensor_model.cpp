#include "edgevio/sim/sensor_model.h"

#include <algorithm>
#include <cmath>

#include "edgevio/sim/random.h"

namespace edgevio::sim {

cv::Mat sensorImage(const cv::Mat& radiance, const camera::CameraModel& camera, const SensorEffects& e,
                    std::uint64_t noise_key) {
  cv::Mat out(radiance.rows, radiance.cols, CV_8UC1);
  const double half_diag2 = 0.25 * (static_cast<double>(radiance.cols) * radiance.cols + static_cast<double>(radiance.rows) * radiance.rows);
  const auto k = static_cast<float>(e.vignetting / half_diag2);
  const auto scale = static_cast<float>(255.0 * e.gain);
  const auto sigma = static_cast<float>(e.noise_sigma);
  const auto cx = static_cast<float>(camera.cx), cy = static_cast<float>(camera.cy);
  for (int v = 0; v < radiance.rows; ++v) {
    const float* in = radiance.ptr<float>(v);
    std::uint8_t* o = out.ptr<std::uint8_t>(v);
    const float dy2 = (static_cast<float>(v) - cy) * (static_cast<float>(v) - cy);
    for (int u = 0; u < radiance.cols; ++u) {
      const float dx = static_cast<float>(u) - cx;
      float value = scale * in[u] * (1.0f - k * (dx * dx + dy2));
      if (sigma > 0.0f) {
        // Irwin-Hall: the sum of four uniforms (16 bits each of one hash) minus
        // 2 has variance 1/3; scaled by √3 it approximates N(0, 1) within ±3.46.
        const std::uint64_t h = splitmix64(noise_key + static_cast<std::uint64_t>(v) * 65536u + static_cast<std::uint64_t>(u));
        const float sum = static_cast<float>((h & 0xFFFF) + ((h >> 16) & 0xFFFF) + ((h >> 32) & 0xFFFF) + (h >> 48)) * (1.0f / 65536.0f);
        value += sigma * 1.7320508f * (sum - 2.0f);
      }
      o[u] = static_cast<std::uint8_t>(std::clamp(value + 0.5f, 0.0f, 255.0f));
    }
  }
  return out;
}

}  // namespace edgevio::sim
