#include "edgevio/sim/imu_synth.h"

#include <cmath>

#include "edgevio/common/time.h"
#include "edgevio/sim/random.h"

namespace edgevio::sim {

SynthesizedImu synthesizeImu(const SplineTrajectory& trajectory, std::int64_t begin_ns, std::int64_t end_ns,
                             const ImuSynthOptions& o, std::uint64_t seed) {
  SynthesizedImu out;
  const auto step = static_cast<std::int64_t>(std::llround(1e9 / o.densities.rate_hz));
  const double dt = toSeconds(step);
  Rng rng(hashCombine(seed, 0x1a5));
  const auto gaussian3 = [&] { return Vec3(rng.gaussian(), rng.gaussian(), rng.gaussian()); };
  Vec3 bg = Vec3::Zero(), ba = Vec3::Zero();
  if (o.noise) {
    bg = o.initial_gyro_bias_sigma * gaussian3();
    ba = o.initial_accel_bias_sigma * gaussian3();
  }
  const double sg = o.densities.gyro_noise_density / std::sqrt(dt), sa = o.densities.accel_noise_density / std::sqrt(dt);
  const double wg = o.densities.gyro_random_walk * std::sqrt(dt), wa = o.densities.accel_random_walk * std::sqrt(dt);
  for (std::int64_t t = begin_ns; t <= end_ns; t += step) {
    const KinematicState s = trajectory.evaluate(t);
    imu::ImuSample m;
    m.t_ns = t;
    m.gyro = s.omega_b + bg;
    m.accel = s.T_w_b.so3().inverse() * (s.a_w + Vec3(0.0, 0.0, kGravity)) + ba;
    if (o.noise) {
      m.gyro += sg * gaussian3();
      m.accel += sa * gaussian3();
    }
    out.samples.push_back(m);
    out.b_g.push_back(bg);
    out.b_a.push_back(ba);
    if (o.noise) {
      bg += wg * gaussian3();
      ba += wa * gaussian3();
    }
  }
  return out;
}

}  // namespace edgevio::sim
