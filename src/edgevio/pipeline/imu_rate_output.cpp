#include "edgevio/pipeline/imu_rate_output.h"

#include <algorithm>

#include <pthread.h>

#include "edgevio/pipeline/threaded_pipeline.h"

namespace edgevio::pipeline {

ImuRateOutput::ImuRateOutput(const std::vector<imu::ImuSample>& imu, double max_gap_s,
                             const std::string& path, bool realtime, std::int64_t t_first_frame, Clock::time_point start)
    : imu_(imu),
      propagator_(max_gap_s),
      writer_(path, io::TrajectoryFormat::kTum),
      realtime_(realtime),
      t_first_frame_(t_first_frame),
      start_(start) {
  // The readings before the first frame only seed the interpolation at its time.
  next_ = static_cast<std::size_t>(std::upper_bound(imu_.begin(), imu_.end(), t_first_frame,
                                                    [](std::int64_t t, const imu::ImuSample& s) { return t < s.t_ns; }) -
                                   imu_.begin());
  if (next_ > 0) propagator_.propagate(imu_[next_ - 1]);
  if (realtime_) thread_ = std::thread([this] { releaseReadings(); });
}

ImuRateOutput::~ImuRateOutput() {
  if (thread_.joinable()) finish(t_first_frame_);
}

void ImuRateOutput::write(const imu::ImuSample& reading) {
  const std::optional<imu::NavState> x = propagator_.propagate(reading);
  // A time offset estimate that grew moves the camera times back: a time
  // already written has its pose.
  if (x && reading.t_ns - time_offset_ns_ > last_written_ns_) {
    io::TrajectorySample s;
    s.t_ns = reading.t_ns - time_offset_ns_;
    last_written_ns_ = s.t_ns;
    s.T_w_b = geometry::SE3(x->R_w_b, x->p_w);
    writer_.write(s);
  }
}

void ImuRateOutput::publish(std::int64_t t_ns, const imu::NavState& x, std::int64_t time_offset_ns) {
  if (realtime_) {
    const std::lock_guard<std::mutex> lock(mutex_);
    mailbox_ = Estimate{t_ns, time_offset_ns, x};
    return;
  }
  // Offline: the readings up to this frame come from the estimate before it.
  const std::int64_t t_imu = t_ns + time_offset_ns;
  for (; next_ < imu_.size() && imu_[next_].t_ns <= t_imu; ++next_) write(imu_[next_]);
  propagator_.setEstimate(t_imu, x);
  time_offset_ns_ = time_offset_ns;
}

void ImuRateOutput::releaseReadings() {
  nameThread("ev-imu-rate");
  // A reading must not wait for a core behind the frame threads: real-time
  // priority where the process may have it (root, CAP_SYS_NICE or an rtprio
  // limit), otherwise the normal one (summary.json says which).
  sched_param priority{};
  priority.sched_priority = 1;
  realtime_priority_ = pthread_setschedparam(pthread_self(), SCHED_FIFO, &priority) == 0;
  for (; next_ < imu_.size(); ++next_) {
    const imu::ImuSample& reading = imu_[next_];
    const Clock::time_point released = start_ + std::chrono::nanoseconds(reading.t_ns - t_first_frame_);
    {
      std::unique_lock<std::mutex> lock(mutex_);
      if (stop_signal_.wait_until(lock, released, [this] { return stop_; })) return;
      if (mailbox_) {
        propagator_.setEstimate(mailbox_->t_ns + mailbox_->time_offset_ns, mailbox_->x);
        time_offset_ns_ = mailbox_->time_offset_ns;
        mailbox_.reset();
      }
    }
    const std::size_t before = writer_.count();
    write(reading);
    if (writer_.count() > before)
      latencies_ms_.push_back(std::chrono::duration<double, std::milli>(Clock::now() - released).count());
  }
}

std::vector<double> ImuRateOutput::finish(std::int64_t t_last_frame) {
  if (!realtime_) {
    for (; next_ < imu_.size() && imu_[next_].t_ns <= t_last_frame + time_offset_ns_; ++next_) write(imu_[next_]);
    return {};
  }
  {
    const std::lock_guard<std::mutex> lock(mutex_);
    stop_ = true;
  }
  stop_signal_.notify_all();
  if (thread_.joinable()) thread_.join();
  return latencies_ms_;
}

}  // namespace edgevio::pipeline
