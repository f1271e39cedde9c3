#include "edgevio/sim/trajectory_source.h"

#include <algorithm>
#include <cmath>

#include "edgevio/common/error.h"
#include "edgevio/common/format.h"
#include "edgevio/common/time.h"

namespace edgevio::sim {

using geometry::SE3;
using geometry::SO3;

namespace {

constexpr double kGravity = 9.81;

/// 0 → 1 with zero first and second derivatives at both ends (quintic smoothstep).
double smootherstep(double x) {
  x = std::clamp(x, 0.0, 1.0);
  return x * x * x * (x * (6.0 * x - 15.0) + 10.0);
}

/// Camera orientation in the world from yaw (about z), pitch (nose up) and roll
/// (about the viewing direction): camera z forward, x right, y down.
SO3 cameraOrientation(double yaw, double pitch, double roll) {
  const Vec3 f(std::cos(yaw) * std::cos(pitch), std::sin(yaw) * std::cos(pitch), std::sin(pitch));
  const Vec3 right0 = f.cross(Vec3::UnitZ()).normalized();  // level right
  const Vec3 down0 = f.cross(right0);
  const Vec3 right = std::cos(roll) * right0 + std::sin(roll) * down0;
  const Vec3 down = f.cross(right);
  Mat3 R;
  R.col(0) = right;
  R.col(1) = down;
  R.col(2) = f;
  return SO3::fromMatrix(R);
}

struct Motion {
  Vec3 p;  ///< camera position, or the body's when body_position is set
  double yaw, pitch, roll;
  bool body_position = false;
};

Motion scenarioMotion(const std::string& name, double tau) {
  // tau: time since the end of the static start; e ramps the motion in over 2 s.
  const double e = smootherstep(tau / 2.0);
  const Vec3 centre(0.0, 0.0, 1.5);
  if (name == "hover") {
    return {centre + e * Vec3(0.15 * std::sin(0.5 * tau), 0.1 * std::sin(0.7 * tau), 0.05 * std::sin(0.9 * tau)),
            e * 0.4 * std::sin(0.2 * tau), e * 0.05 * std::sin(0.6 * tau), e * 0.05 * std::sin(0.8 * tau)};
  }
  if (name == "figure8") {
    const double w = 2 * kPi / 12.0;
    return {centre + e * Vec3(1.5 * std::sin(w * tau), 1.0 * std::sin(2 * w * tau), 0.2 * std::sin(0.5 * w * tau)),
            e * 0.6 * std::sin(w * tau), e * 0.05 * std::sin(3 * w * tau), e * 0.15 * std::sin(2 * w * tau)};
  }
  if (name == "aggressive") {
    const double w = 2 * kPi / 6.0;
    return {centre + e * Vec3(1.6 * std::sin(w * tau) + 0.15 * std::sin(2 * kPi * 1.3 * tau),
                              1.0 * std::sin(2 * w * tau), 0.25 * std::sin(2 * kPi * 1.5 * tau)),
            e * (0.8 * std::sin(w * tau) + 0.25 * std::sin(2 * kPi * 0.9 * tau)),
            e * 0.3 * std::sin(2 * kPi * 1.1 * tau + 1.0), e * 0.55 * std::sin(2 * kPi * 1.6 * tau)};
  }
  if (name == "throw") {
    // Walking a circle (0.7 m/s) with the rig in hand at 1.2 m, facing along
    // the walk; every 3 s a 0.7 s ballistic flight with a full roll.
    const double radius = 2.0, speed = 0.7, hand = 1.2, period = 3.0, flight = 0.7;
    const double walk = e * speed * tau;  // arc length, ramped in
    const double phi = walk / radius;
    Vec3 p(radius * std::sin(phi), radius * (1.0 - std::cos(phi)), hand);
    double roll = 0.0;
    if (tau > 2.0) {
      const double in_cycle = std::fmod(tau - 2.0, period);
      if (in_cycle < flight) {
        const double v0 = 0.5 * kGravity * flight;
        p.z() += v0 * in_cycle - 0.5 * kGravity * in_cycle * in_cycle;
        roll = 2 * kPi * smootherstep(in_cycle / flight);
      }
    }
    // A thrown rig spins about its centre of mass: the body (IMU) position,
    // not the camera's, follows the ballistic arc.
    return {p, phi, 0.0, roll, true};
  }
  throw InputError("unknown scenario '" + name + "' (expected hover, figure8, aggressive or throw)");
}

}  // namespace

const std::vector<std::string>& scenarioNames() {
  static const std::vector<std::string> names = {"hover", "figure8", "aggressive", "throw"};
  return names;
}

io::Trajectory scenarioSamples(const std::string& name, double duration_s, double static_start_s, const SE3& T_b_c) {
  const std::int64_t step = 5000000;  // 200 Hz
  const SO3 R_c_b = T_b_c.so3().inverse();
  io::Trajectory out;
  const auto n = static_cast<std::int64_t>(std::ceil(duration_s * 1e9 / static_cast<double>(step)));
  for (std::int64_t k = 0; k <= n; ++k) {
    const double t = toSeconds(k * step);
    const Motion m = scenarioMotion(name, std::max(0.0, t - static_start_s));
    io::TrajectorySample s;
    s.t_ns = kScenarioStartNs + k * step;
    // R_w_b = R_w_c · R_c_b; the body position follows from the camera's.
    const SO3 R_w_c = cameraOrientation(m.yaw, m.pitch, m.roll);
    const SO3 R_w_b = R_w_c * R_c_b;
    s.T_w_b = SE3(R_w_b, m.body_position ? m.p : Vec3(m.p - R_w_b * T_b_c.translation()));
    out.push_back(s);
  }
  return out;
}

int removePositionSteps(io::Trajectory& samples, double max_accel_mps2, double spread_s) {
  constexpr std::size_t kSide = 5;  // neighbours on each side of an increment
  const std::size_t n = samples.size();
  if (max_accel_mps2 <= 0.0 || n < 2 * kSide + 2) return 0;
  const auto dt = [&](std::size_t i) { return toSeconds(samples[i].t_ns - samples[i - 1].t_ns); };
  // Velocity of increment i (i = 1..n−1); equal timestamps carry no velocity.
  std::vector<Vec3> vel(n, Vec3::Zero());
  for (std::size_t i = 1; i < n; ++i)
    if (dt(i) > 0.0) vel[i] = (samples[i].T_w_b.translation() - samples[i - 1].T_w_b.translation()) / dt(i);

  std::vector<Vec3> fixed = vel;
  std::vector<bool> stepped(n, false);  // sample i is the far end of a replaced increment
  int replaced = 0;
  // Componentwise medians of the kSide increments before i, after i, and of both.
  const auto median = [&](std::size_t first, std::size_t last, std::size_t skip) {
    Vec3 m;
    std::vector<double> window;
    for (int axis = 0; axis < 3; ++axis) {
      window.clear();
      for (std::size_t j = first; j <= last; ++j)
        if (j != skip) window.push_back(vel[j][axis]);
      std::sort(window.begin(), window.end());
      const std::size_t h = window.size() / 2;
      m[axis] = window.size() % 2 == 1 ? window[h] : 0.5 * (window[h - 1] + window[h]);
    }
    return m;
  };
  for (std::size_t i = 1 + kSide; i + kSide < n; ++i) {
    if (!(dt(i) > 0.0)) continue;
    const double limit = max_accel_mps2 * dt(i);
    const Vec3 both = median(i - kSide, i + kSide, i);
    // A step disagrees with the motion on both sides; a kink (a velocity jump,
    // e.g. a scenario's throw) agrees with one of them and is kept.
    if ((vel[i] - both).norm() > limit && (vel[i] - median(i - kSide, i - 1, n)).norm() > limit &&
        (vel[i] - median(i + 1, i + kSide, n)).norm() > limit) {
      fixed[i] = both;
      stepped[i] = true;
      ++replaced;
    }
  }
  if (replaced == 0) return 0;

  // Re-summed positions, and the offset of the file from them. The offset is
  // not observed at a step's far end: that keeps a spike's peak (both of its
  // increments replaced) out of the average altogether.
  std::vector<Vec3> summed(n);
  summed[0] = samples[0].T_w_b.translation();
  for (std::size_t i = 1; i < n; ++i) summed[i] = summed[i - 1] + fixed[i] * dt(i);
  std::vector<Vec3> prefix(n + 1, Vec3::Zero());
  std::vector<int> count(n + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const bool observed = !stepped[i];
    prefix[i + 1] = prefix[i] + (observed ? Vec3(samples[i].T_w_b.translation() - summed[i]) : Vec3::Zero());
    count[i + 1] = count[i] + (observed ? 1 : 0);
  }
  // Moving average over ±spread_s/2 (fewer samples near the ends).
  const auto half_ns = toNanoseconds(0.5 * spread_s);
  std::size_t lo = 0, hi = 0;
  for (std::size_t i = 0; i < n; ++i) {
    while (samples[lo].t_ns < samples[i].t_ns - half_ns) ++lo;
    while (hi < n && samples[hi].t_ns <= samples[i].t_ns + half_ns) ++hi;
    const int k = count[hi] - count[lo];
    const Vec3 mean = k > 0 ? Vec3((prefix[hi] - prefix[lo]) / k) : Vec3::Zero();
    samples[i].T_w_b = SE3(samples[i].T_w_b.so3(), summed[i] + mean);
  }
  return replaced;
}

SplineTrajectory fitSpline(const io::Trajectory& samples, std::int64_t begin_ns, std::int64_t end_ns,
                           double knot_dt_s, double max_gap_s, const std::string& source) {
  const auto seconds = [](std::int64_t t) { return formatText("%.3f", toSeconds(t)); };
  if (samples.size() < 2) throw InputError(source, 0, "trajectory has fewer than 2 poses");
  if (end_ns <= begin_ns) throw InputError(source, 0, "empty time span requested");
  if (begin_ns < samples.front().t_ns || end_ns > samples.back().t_ns)
    throw InputError(source, 0,
                     "trajectory covers [" + seconds(samples.front().t_ns) + ", " + seconds(samples.back().t_ns) +
                         "] s but [" + seconds(begin_ns) + ", " + seconds(end_ns) +
                         "] s was requested (check --start and --duration)");
  const auto gap_ns = toNanoseconds(max_gap_s);
  for (std::size_t i = 1; i < samples.size(); ++i) {
    if (samples[i].t_ns < begin_ns - 2 * gap_ns || samples[i - 1].t_ns > end_ns + 2 * gap_ns) continue;
    if (samples[i].t_ns - samples[i - 1].t_ns > gap_ns)
      throw InputError(source, 0,
                       "gap of " + seconds(samples[i].t_ns - samples[i - 1].t_ns) + " s in the trajectory at t = " +
                           seconds(samples[i - 1].t_ns) + " s (longest allowed: sim.max_trajectory_gap_s = " +
                           std::to_string(max_gap_s) + " s)");
  }
  const auto dt = toNanoseconds(knot_dt_s);
  const std::int64_t n = (end_ns - begin_ns + dt - 1) / dt + 3;
  std::vector<SE3> cps;
  for (std::int64_t k = 0; k < n; ++k) {
    // Control point k at begin + (k − 1)·dt, looked up by interpolation (clamped at the ends).
    const std::int64_t t = std::clamp(begin_ns + (k - 1) * dt, samples.front().t_ns, samples.back().t_ns);
    const auto it = std::lower_bound(samples.begin(), samples.end(), t,
                                     [](const io::TrajectorySample& s, std::int64_t v) { return s.t_ns < v; });
    if (it == samples.begin()) {
      cps.push_back(it->T_w_b);
    } else {
      const auto& a = *(it - 1);
      const auto& b = *it;
      const double w = b.t_ns == a.t_ns ? 0.0 : static_cast<double>(t - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
      cps.push_back(geometry::interpolate(a.T_w_b, b.T_w_b, w));
    }
  }
  return SplineTrajectory(begin_ns, dt, std::move(cps));
}

}  // namespace edgevio::sim
