#pragma once
// trajectory_imu_rate_tum.txt (IMU modes): the pose of every IMU reading after
// the first estimate, propagated from the newest estimate (imu/imu_rate.h).
// Offline each frame's estimate counts as available at its own time: the
// readings up to a frame are propagated from the frame before it, so the
// file is deterministic. In real time a thread releases each reading at its
// timestamp, as the driver releases frames, and propagates it from the newest
// estimate the tracking thread has published by then; the time from a
// reading's release to its pose is its latency.
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "edgevio/imu/imu_rate.h"
#include "edgevio/io/trajectory_io.h"

namespace edgevio::pipeline {

class ImuRateOutput {
 public:
  using Clock = std::chrono::steady_clock;

  /// `t_first_frame`: the first frame's time, released at `start` in real time.
  ImuRateOutput(const std::vector<imu::ImuSample>& imu, double max_gap_s, const std::string& path,
                bool realtime, std::int64_t t_first_frame, Clock::time_point start);
  ~ImuRateOutput();
  ImuRateOutput(const ImuRateOutput&) = delete;
  ImuRateOutput& operator=(const ImuRateOutput&) = delete;

  /// The estimate of the body at a frame's time t_ns (from the tracking
  /// thread), which is IMU time t_ns + time_offset_ns (the window's camera-IMU
  /// time offset): the poses that follow are written at camera times, each
  /// reading's time minus that offset.
  void publish(std::int64_t t_ns, const imu::NavState& x, std::int64_t time_offset_ns = 0);
  /// After the last frame (t_last_frame): offline, the readings up to it; in
  /// real time, stops the thread. Returns every pose's latency [ms] (real time; empty offline).
  std::vector<double> finish(std::int64_t t_last_frame);
  /// Poses written.
  std::size_t poses() const { return writer_.count(); }
  /// Real time: whether the reading thread got real-time scheduling priority (after finish()).
  bool realtimePriority() const { return realtime_priority_; }

 private:
  void write(const imu::ImuSample& reading);
  void releaseReadings();

  const std::vector<imu::ImuSample>& imu_;
  imu::ImuRatePropagator propagator_;
  io::TrajectoryWriter writer_;
  bool realtime_;
  std::int64_t t_first_frame_;
  Clock::time_point start_;
  std::size_t next_ = 0;  ///< offline: the next reading to propagate
  std::int64_t time_offset_ns_ = 0;  ///< the newest estimate's camera-IMU time offset
  std::int64_t last_written_ns_ = std::numeric_limits<std::int64_t>::min();  ///< the newest pose's time
  std::vector<double> latencies_ms_;
  bool realtime_priority_ = false;

  // Real time: the tracking thread's newest estimate, handed to the reading thread.
  std::mutex mutex_;
  std::condition_variable stop_signal_;
  bool stop_ = false;
  struct Estimate {
    std::int64_t t_ns, time_offset_ns;
    imu::NavState x;
  };
  std::optional<Estimate> mailbox_;
  std::thread thread_;
};

}  // namespace edgevio::pipeline
