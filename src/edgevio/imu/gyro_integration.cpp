#include "edgevio/imu/gyro_integration.h"

#include <algorithm>
#include <cmath>
#include "edgevio/common/time.h"

namespace edgevio::imu {

using geometry::SO3;

namespace {
ImuSample interpolate(const ImuSample& a, const ImuSample& b, std::int64_t t) {
  const double w = b.t_ns == a.t_ns ? 0.0 : static_cast<double>(t - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  ImuSample s;
  s.t_ns = t;
  s.gyro = (1.0 - w) * a.gyro + w * b.gyro;
  s.accel = (1.0 - w) * a.accel + w * b.accel;
  return s;
}
}  // namespace

bool forEachImuInterval(const std::vector<ImuSample>& imu, std::int64_t t0, std::int64_t t1,
                        const std::function<void(double, const Vec3&, const Vec3&, const Vec3&, const Vec3&)>& f) {
  if (imu.size() < 2 || t1 <= t0 || imu.front().t_ns > t0 || imu.back().t_ns < t1) return false;
  auto it = std::upper_bound(imu.begin(), imu.end(), t0, [](std::int64_t t, const ImuSample& s) { return t < s.t_ns; });
  // it: first sample after t0; the interval [t0, t1] is cut at every sample inside it.
  ImuSample prev = interpolate(*(it - 1), *it, t0);
  while (prev.t_ns < t1) {
    const std::int64_t t_next = std::min(it->t_ns, t1);
    const ImuSample next = t_next == it->t_ns ? *it : interpolate(*(it - 1), *it, t_next);
    f(toSeconds(next.t_ns - prev.t_ns), prev.accel, prev.gyro, next.accel, next.gyro);
    prev = next;
    if (t_next == it->t_ns && it + 1 != imu.end()) ++it;
  }
  return true;
}

bool imuGapWithin(const std::vector<ImuSample>& imu, std::int64_t t0, std::int64_t t1, double max_gap_s) {
  const auto byTime = [](const ImuSample& s, std::int64_t t) { return s.t_ns < t; };
  auto it = std::lower_bound(imu.begin(), imu.end(), t0, byTime);
  if (it != imu.begin()) --it;
  for (; it != imu.end() && it + 1 != imu.end() && it->t_ns < t1; ++it)
    if (toSeconds((it + 1)->t_ns - it->t_ns) > max_gap_s) return true;
  return false;
}

bool integrateGyro(const std::vector<ImuSample>& imu, std::int64_t t0, std::int64_t t1, const Vec3& bias, double max_gap_s,
                   SO3* R) {
  *R = SO3();
  if (imuGapWithin(imu, t0, t1, max_gap_s)) return false;
  SO3 acc;
  const bool ok = forEachImuInterval(imu, t0, t1, [&](double dt, const Vec3&, const Vec3& w0, const Vec3&, const Vec3& w1) {
    acc = acc * SO3::exp((0.5 * (w0 + w1) - bias) * dt);
  });
  *R = acc;
  return ok;
}

namespace {
// A spread needs at least three chunk means, and the mean reading ten samples.
constexpr std::size_t kMinChunks = 3, kMinSamples = 10;
// Below this mean specific force the IMU is falling or its log is broken:
// there is no "up" to align with (at rest it reads g = 9.81).
constexpr double kMinSpecificForce = 5.0;
}  // namespace

StaticInit staticInitialization(const std::vector<ImuSample>& imu, std::int64_t t0, double window_s, double chunk_s,
                                double accel_std_max, double gyro_std_max) {
  const std::int64_t chunk_ns = toNanoseconds(chunk_s);
  StaticInit s;
  const auto t1 = t0 + toNanoseconds(window_s);
  std::vector<Vec3> chunk_a, chunk_g;
  Vec3 sa = Vec3::Zero(), sg = Vec3::Zero(), ca = Vec3::Zero(), cg = Vec3::Zero();
  int in_chunk = 0;
  std::int64_t chunk_end = t0 + chunk_ns;
  for (const auto& m : imu) {
    if (m.t_ns < t0 || m.t_ns > t1) continue;
    while (m.t_ns >= chunk_end) {
      if (in_chunk > 0) {
        chunk_a.push_back(ca / in_chunk);
        chunk_g.push_back(cg / in_chunk);
      }
      ca = cg = Vec3::Zero();
      in_chunk = 0;
      chunk_end += chunk_ns;
    }
    sa += m.accel;
    sg += m.gyro;
    ca += m.accel;
    cg += m.gyro;
    ++in_chunk;
    ++s.samples;
  }
  if (s.samples < kMinSamples || chunk_a.size() < kMinChunks) return s;
  const double n = static_cast<double>(s.samples);
  s.mean_accel = sa / n;
  const Vec3 mg = sg / n;
  const auto spread = [](const std::vector<Vec3>& v) {
    Vec3 mean = Vec3::Zero();
    for (const Vec3& x : v) mean += x;
    mean /= static_cast<double>(v.size());
    double ss = 0.0;
    for (const Vec3& x : v) ss += (x - mean).squaredNorm();
    return std::sqrt(ss / static_cast<double>(v.size()));
  };
  if (s.mean_accel.norm() < kMinSpecificForce) return s;
  // R_w_b maps the measured "up" (specific force at rest) onto world z; the
  // rotation is the smallest one (so yaw is left at its zero). In motion the
  // window's mean specific force is still mostly gravity (a swing of Δv over
  // the window tilts it by about Δv / (g·window)): a far better starting point
  // for the estimator than a level attitude, though not a measurement of tilt.
  s.R_w_b = SO3(Quat::FromTwoVectors(s.mean_accel.normalized(), Vec3::UnitZ()));
  s.is_static = spread(chunk_a) < accel_std_max && spread(chunk_g) < gyro_std_max;
  if (s.is_static) s.gyro_bias = mg;
  return s;
}

}  // namespace edgevio::imu
