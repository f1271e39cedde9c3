#pragma once
#include <cstdint>

#include "edgevio/geometry/types.h"

namespace edgevio::io {

/// One IMU reading in the IMU (body) frame.
struct ImuSample {
  std::int64_t t_ns = 0;
  Vec3 gyro = Vec3::Zero();   ///< angular rate ω̂ [rad/s]
  Vec3 accel = Vec3::Zero();  ///< specific force â [m/s²]
};

}  // namespace edgevio::io
