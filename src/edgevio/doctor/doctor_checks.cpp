// The doctor's checks on plain data: the IMU log, and the camera's rotations
// against the gyroscope's (time offset, hand-eye rotation).
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <optional>

#include "edgevio/common/time.h"
#include "edgevio/doctor/doctor.h"
#include "edgevio/imu/gyro_integration.h"

namespace edgevio::doctor {

namespace {

constexpr double kRadToDeg = 180.0 / M_PI;

/// Mean and per-axis standard deviation of samples [begin, end) of one sensor.
struct AxisStats {
  Vec3 mean = Vec3::Zero(), std = Vec3::Zero();
};
template <class Get>
AxisStats axisStats(const std::vector<imu::ImuSample>& imu, std::size_t begin, std::size_t end, Get get) {
  AxisStats s;
  const double n = static_cast<double>(end - begin);
  for (std::size_t i = begin; i < end; ++i) s.mean += get(imu[i]);
  s.mean /= n;
  for (std::size_t i = begin; i < end; ++i) s.std += (get(imu[i]) - s.mean).cwiseAbs2();
  s.std = (s.std / std::max(1.0, n - 1)).cwiseSqrt();
  return s;
}

/// Camera-IMU rotation and gyroscope bias from matched rates: the R and b
/// minimising sum |gyro_k - R camera_k - b|^2 (Procrustes with a constant:
/// Kabsch on the centred rates, then b from the means).
struct HandEye {
  Mat3 R = Mat3::Identity();
  Vec3 b = Vec3::Zero();
};
HandEye handEye(const std::vector<Vec3>& camera, const std::vector<Vec3>& gyro, const std::vector<bool>& use) {
  Vec3 mc = Vec3::Zero(), mg = Vec3::Zero();
  double n = 0;
  for (std::size_t k = 0; k < camera.size(); ++k)
    if (use[k]) {
      mc += camera[k];
      mg += gyro[k];
      n += 1;
    }
  HandEye h;
  if (n < 3) return h;
  mc /= n;
  mg /= n;
  Mat3 H = Mat3::Zero();
  for (std::size_t k = 0; k < camera.size(); ++k)
    if (use[k]) H += (camera[k] - mc) * (gyro[k] - mg).transpose();
  const Eigen::JacobiSVD<Mat3> svd(H, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Mat3 D = Mat3::Identity();
  D(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1.0 : 1.0;
  h.R = svd.matrixV() * D * svd.matrixU().transpose();
  h.b = mg - h.R * mc;
  return h;
}

/// The gyroscope's mean rate over the IMU times [t0 + offset, t1 + offset]
/// (the log of its rotation over the interval's length), without bias.
std::optional<Vec3> gyroRate(const std::vector<imu::ImuSample>& imu, const FrameRotation& r, std::int64_t offset_ns,
                             double max_gap_s) {
  geometry::SO3 R;
  if (!imu::integrateGyro(imu, r.t0_ns + offset_ns, r.t1_ns + offset_ns, Vec3::Zero(), max_gap_s, &R)) return std::nullopt;
  return R.log() / toSeconds(r.t1_ns - r.t0_ns);
}

}  // namespace

ImuCheck checkImu(const std::vector<imu::ImuSample>& imu, double max_gap_s, const DoctorOptions& options) {
  ImuCheck c;
  c.samples = imu.size();
  if (imu.size() < 2) return c;
  std::vector<double> spacing;
  spacing.reserve(imu.size() - 1);
  for (std::size_t i = 1; i < imu.size(); ++i) {
    const double dt = toSeconds(imu[i].t_ns - imu[i - 1].t_ns);
    spacing.push_back(dt);
    if (dt > max_gap_s) {
      ++c.gaps;
      c.longest_gap_s = std::max(c.longest_gap_s, dt);
    }
  }
  const double period = median(spacing);
  c.rate_hz = period > 0 ? 1.0 / period : 0.0;

  // A clipped channel sits at its extreme value for several readings; a
  // real signal's extreme (a float of many digits) is reached once.
  for (int ch = 0; ch < 6; ++ch) {
    const auto value = [&](const imu::ImuSample& s) { return ch < 3 ? s.gyro[ch] : s.accel[ch - 3]; };
    double lo = value(imu[0]), hi = lo;
    for (const auto& s : imu) {
      lo = std::min(lo, value(s));
      hi = std::max(hi, value(s));
    }
    int at_lo = 0, at_hi = 0;
    for (const auto& s : imu) {
      at_lo += value(s) == lo;
      at_hi += value(s) == hi;
    }
    constexpr int kClippedRepeats = 3;
    if (at_lo >= kClippedRepeats) c.saturated_samples += at_lo;
    if (at_hi >= kClippedRepeats && hi != lo) c.saturated_samples += at_hi;
  }

  // Standstill: the longest run of still half-windows (per-axis spreads
  // under the thresholds) at least doctor.standstill_min_s long.
  if (!(period > 0)) return c;
  const auto half = static_cast<std::size_t>(std::max(2.0, std::round(0.5 * options.standstill_min_s / period)));
  const auto gyro = [](const imu::ImuSample& s) { return s.gyro; };
  const auto accel = [](const imu::ImuSample& s) { return s.accel; };
  std::size_t best_begin = 0, best_end = 0, run_begin = 0;
  bool in_run = false;
  for (std::size_t w = 0; w + half <= imu.size(); w += half) {
    const bool still = axisStats(imu, w, w + half, gyro).std.maxCoeff() < options.standstill_gyro_std_rad_s &&
                       axisStats(imu, w, w + half, accel).std.maxCoeff() < options.standstill_accel_std_mps2 &&
                       toSeconds(imu[w + half - 1].t_ns - imu[w].t_ns) < 1.5 * period * static_cast<double>(half);
    if (still && !in_run) run_begin = w;
    in_run = still;
    if (still && w + half - run_begin > best_end - best_begin) {
      best_begin = run_begin;
      best_end = w + half;
    }
  }
  if (best_end <= best_begin || toSeconds(imu[best_end - 1].t_ns - imu[best_begin].t_ns) < options.standstill_min_s) return c;
  c.standstill_s = toSeconds(imu[best_end - 1].t_ns - imu[best_begin].t_ns);
  c.standstill_start_s = toSeconds(imu[best_begin].t_ns - imu[0].t_ns);
  const AxisStats g = axisStats(imu, best_begin, best_end, gyro), a = axisStats(imu, best_begin, best_end, accel);
  c.gyro_bias = g.mean;
  // Discrete white noise of std. dev. sigma_d at period dt has the density sigma_d * sqrt(dt).
  c.gyro_noise_density = std::sqrt(g.std.squaredNorm() / 3.0) * std::sqrt(period);
  c.accel_noise_density = std::sqrt(a.std.squaredNorm() / 3.0) * std::sqrt(period);
  double gravity = 0;
  for (std::size_t i = best_begin; i < best_end; ++i) gravity += imu[i].accel.norm();
  c.gravity_mps2 = gravity / static_cast<double>(best_end - best_begin);
  return c;
}

MotionCheck checkMotion(const std::vector<FrameRotation>& rotations, const std::vector<imu::ImuSample>& imu,
                        const geometry::SO3& R_b_c_calibrated, double max_gap_s, const DoctorOptions& options) {
  MotionCheck m;
  m.rotations = rotations.size();
  const int steps = static_cast<int>(std::round(options.max_time_offset_ms));
  const auto offsetNs = [](double ms) { return static_cast<std::int64_t>(std::llround(ms * 1e6)); };

  // The gyroscope's rate over every pair at every offset of a 1 ms grid;
  // only pairs the IMU covers at every offset take part (the same pairs for
  // every offset, so that costs compare).
  std::vector<FrameRotation> pairs;
  std::vector<Vec3> camera;
  std::vector<std::vector<Vec3>> gyro_at;  // [offset][pair]
  for (const FrameRotation& r : rotations) {
    if (r.t1_ns <= r.t0_ns) continue;
    std::vector<Vec3> rates;
    for (int j = -steps; j <= steps; ++j) {
      const auto w = gyroRate(imu, r, offsetNs(j), max_gap_s);
      if (!w) break;
      rates.push_back(*w);
    }
    if (rates.size() != static_cast<std::size_t>(2 * steps + 1)) continue;
    pairs.push_back(r);
    camera.push_back(r.R_c0_c1.log() / toSeconds(r.t1_ns - r.t0_ns));
    if (gyro_at.empty()) gyro_at.resize(rates.size());
    for (std::size_t j = 0; j < rates.size(); ++j) gyro_at[j].push_back(rates[j]);
  }
  if (pairs.size() < 10) return m;

  // Observability: the camera's rate must vary about two axes.
  Vec3 mean = Vec3::Zero();
  for (const Vec3& w : camera) mean += w;
  mean /= static_cast<double>(camera.size());
  Mat3 cov = Mat3::Zero();
  for (const Vec3& w : camera) cov += (w - mean) * (w - mean).transpose();
  cov /= static_cast<double>(camera.size());
  const Eigen::SelfAdjointEigenSolver<Mat3> eig(cov);
  for (int i = 0; i < 3; ++i) m.rotation_rate_std_rad_s[i] = std::sqrt(std::max(0.0, eig.eigenvalues()[2 - i]));
  m.observable = m.rotation_rate_std_rad_s[1] >= options.min_rotation_rate_rad_s;

  // 1. The offset where the rates' magnitudes agree best (needs no rotation).
  std::vector<bool> use(pairs.size(), true);
  const auto magnitudeCost = [&](std::size_t j) {
    double c = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k) c += std::pow(gyro_at[j][k].norm() - camera[k].norm(), 2);
    return c;
  };
  std::size_t best = 0;
  for (std::size_t j = 1; j < gyro_at.size(); ++j)
    if (magnitudeCost(j) < magnitudeCost(best)) best = j;

  // 2. Mis-tracked pairs are dropped: an alignment that passed its self
  // check in a wrong basin gives a rate far off the gyroscope's, and a few
  // of those would turn a least-squares rotation by degrees. First by the
  // rates' magnitudes (no rotation needed), then twice by the residual of
  // the rotation and bias fitted to the pairs kept; each time a pair is kept
  // within 3x the median of all pairs' residuals.
  const auto keepWithin3Medians = [&](const std::vector<double>& residual) {
    const double limit = 3.0 * median(residual);
    for (std::size_t k = 0; k < pairs.size(); ++k) use[k] = residual[k] <= limit;
  };
  std::vector<double> residual(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) residual[k] = std::abs(gyro_at[best][k].norm() - camera[k].norm());
  keepWithin3Medians(residual);
  for (int round = 0; round < 2; ++round) {
    const HandEye fit = handEye(camera, gyro_at[best], use);
    for (std::size_t k = 0; k < pairs.size(); ++k) residual[k] = (gyro_at[best][k] - fit.R * camera[k] - fit.b).norm();
    keepWithin3Medians(residual);
  }
  const auto meanSquaredResidual = [&](const std::vector<Vec3>& gyro, const HandEye& fit) {
    double c = 0, n = 0;
    for (std::size_t k = 0; k < pairs.size(); ++k)
      if (use[k]) {
        c += (gyro[k] - fit.R * camera[k] - fit.b).squaredNorm();
        n += 1;
      }
    return c / std::max(1.0, n);
  };
  m.offset_cost.resize(gyro_at.size());
  for (std::size_t j = 0; j < gyro_at.size(); ++j) m.offset_cost[j] = meanSquaredResidual(gyro_at[j], handEye(camera, gyro_at[j], use));
  best = static_cast<std::size_t>(std::min_element(m.offset_cost.begin(), m.offset_cost.end()) - m.offset_cost.begin());
  m.offsets_ms.resize(gyro_at.size());
  for (std::size_t j = 0; j < gyro_at.size(); ++j) m.offsets_ms[j] = static_cast<double>(static_cast<int>(j) - steps);

  // Sub-millisecond: the parabola through the minimum and its neighbours.
  // Its curvature gives the offset's variance, 2 sigma^2 / S'' with S the
  // sum of squared residuals (Gauss-Newton on one parameter) and sigma^2
  // the residual's variance per component.
  double offset = m.offsets_ms[best], n_used = 0;
  for (bool u : use) n_used += u;
  if (best > 0 && best + 1 < gyro_at.size()) {
    const double cm = m.offset_cost[best - 1], c0 = m.offset_cost[best], cp = m.offset_cost[best + 1];
    const double curvature = cm - 2 * c0 + cp;  // per ms^2, of the mean cost
    if (curvature > 0) {
      offset += 0.5 * (cm - cp) / curvature;
      const double sigma2 = c0 * n_used / std::max(1.0, 3 * n_used - 4);
      m.time_offset_sigma_ms = std::sqrt(2 * sigma2 / (curvature * n_used));
    }
  }
  m.time_offset_ms = offset;

  // 4. Rotation and bias at the refined offset.
  std::vector<Vec3> gyro(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) gyro[k] = gyroRate(imu, pairs[k], offsetNs(offset), max_gap_s).value_or(gyro_at[best][k]);
  const HandEye h = handEye(camera, gyro, use);
  m.R_b_c = geometry::SO3::fromMatrix(h.R);
  m.gyro_bias = h.b;
  m.rotation_error_deg = (R_b_c_calibrated.inverse() * m.R_b_c).log().norm() * kRadToDeg;
  m.residual_rad_s = std::sqrt(meanSquaredResidual(gyro, h));
  const std::int64_t t0 = pairs.front().t0_ns;
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    m.t_s.push_back(toSeconds(pairs[k].t1_ns - t0));
    m.camera_rate.push_back(camera[k].norm());
    m.gyro_rate.push_back((gyro[k] - h.b).norm());
  }
  return m;
}

}  // namespace edgevio::doctor
