#pragma once
// Small IMU helpers the front end needs before the estimator exists:
// rotation from integrating the gyroscope between two times (the initial
// guess of an alignment, METHOD.md §3), and static initialisation
// (METHOD.md §5: roll and pitch from the mean accelerometer reading, gyro bias
// from the mean gyro reading, yaw 0).
#include <cstdint>
#include <functional>
#include <vector>

#include "edgevio/geometry/so3.h"
#include "edgevio/imu/imu_types.h"

namespace edgevio::imu {

/// Calls f(dt_s, acc0, gyr0, acc1, gyr1) for each interval between
/// consecutive readings that cuts [t0, t1], the end readings interpolated
/// linearly at t0 and t1 (the one place the IMU stream is cut at frame
/// times). Returns false, calling nothing, without IMU coverage of [t0, t1].
bool forEachImuInterval(const std::vector<ImuSample>& imu, std::int64_t t0_ns, std::int64_t t1_ns,
                        const std::function<void(double, const Vec3&, const Vec3&, const Vec3&, const Vec3&)>& f);

/// Whether two consecutive readings around [t0, t1] lie more than max_gap_s
/// apart. Judged on the raw readings: cut at frame times, interpolation would
/// bridge a gap in frame-length pieces.
bool imuGapWithin(const std::vector<ImuSample>& imu, std::int64_t t0_ns, std::int64_t t1_ns, double max_gap_s);

/// R_{b(t0) b(t1)}: body rotation from t0 to t1, Π exp((ω̄ − b_g)·Δt) with ω̄ the
/// mean of consecutive samples (midpoint rule), samples clipped to [t0, t1] by
/// linear interpolation. Returns false (and identity) without IMU coverage or
/// across a gap longer than max_gap_s (a rate interpolated over a gap is no
/// measurement).
bool integrateGyro(const std::vector<ImuSample>& imu, std::int64_t t0_ns, std::int64_t t1_ns, const Vec3& gyro_bias,
                   double max_gap_s, geometry::SO3* R_b0_b1);

struct StaticInit {
  bool is_static = false;       ///< the window looked static (low accel and gyro spread)
  geometry::SO3 R_w_b;          ///< gravity-aligned orientation from the mean specific force, yaw 0 (identity without one)
  Vec3 gyro_bias = Vec3::Zero();
  Vec3 mean_accel = Vec3::Zero();
  std::size_t samples = 0;
};

/// Uses the IMU samples in [t0, t0 + window]; static when the spread of the
/// means over chunks of chunk_s is below accel_std_max [m/s²] and
/// gyro_std_max [rad/s] (rotor vibration averages out over a chunk, motion does not).
StaticInit staticInitialization(const std::vector<ImuSample>& imu, std::int64_t t0_ns, double window_s, double chunk_s,
                                double accel_std_max, double gyro_std_max);

}  // namespace edgevio::imu
