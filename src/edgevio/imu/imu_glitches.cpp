#include "edgevio/imu/imu_glitches.h"

#include <algorithm>
#include <array>

namespace edgevio::imu {

namespace {

double median5(std::array<double, 5> v) {
  std::nth_element(v.begin(), v.begin() + 2, v.end());
  return v[2];
}

}  // namespace

std::vector<std::size_t> replaceGlitches(std::vector<ImuSample>* imu, double max_gyro_jump_rad_s, double max_accel_jump_mps2) {
  std::vector<std::size_t> replaced;
  const std::vector<ImuSample>& in = *imu;
  if (in.size() < 5) return replaced;
  // Five readings around a gap are no neighbourhood: they must span at most
  // six typical periods (four, and a late or lost reading).
  std::vector<std::int64_t> dt;
  for (std::size_t i = 1; i < in.size(); ++i) dt.push_back(in[i].t_ns - in[i - 1].t_ns);
  std::nth_element(dt.begin(), dt.begin() + static_cast<std::ptrdiff_t>(dt.size() / 2), dt.end());
  const std::int64_t max_span_ns = 6 * dt[dt.size() / 2];
  std::vector<ImuSample> out = in;  // medians of the original readings, not of replaced ones
  for (std::size_t i = 2; i + 2 < in.size(); ++i) {
    if (in[i + 2].t_ns - in[i - 2].t_ns > max_span_ns) continue;
    Vec3 gyro, accel;
    for (int axis = 0; axis < 3; ++axis) {
      gyro[axis] = median5({in[i - 2].gyro[axis], in[i - 1].gyro[axis], in[i].gyro[axis], in[i + 1].gyro[axis], in[i + 2].gyro[axis]});
      accel[axis] =
          median5({in[i - 2].accel[axis], in[i - 1].accel[axis], in[i].accel[axis], in[i + 1].accel[axis], in[i + 2].accel[axis]});
    }
    const bool gyro_glitch = max_gyro_jump_rad_s > 0 && (in[i].gyro - gyro).cwiseAbs().maxCoeff() > max_gyro_jump_rad_s;
    const bool accel_glitch = max_accel_jump_mps2 > 0 && (in[i].accel - accel).cwiseAbs().maxCoeff() > max_accel_jump_mps2;
    if (!gyro_glitch && !accel_glitch) continue;
    out[i].gyro = gyro;
    out[i].accel = accel;
    replaced.push_back(i);
  }
  *imu = std::move(out);
  return replaced;
}

}  // namespace edgevio::imu
