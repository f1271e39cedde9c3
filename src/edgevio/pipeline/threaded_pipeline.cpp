#include "edgevio/pipeline/threaded_pipeline.h"

#include <atomic>
#include <chrono>
#include <exception>
#include <optional>
#include <thread>

#include <pthread.h>

#include "edgevio/pipeline/bounded_queue.h"

namespace edgevio::pipeline {

namespace {

using Clock = std::chrono::steady_clock;

double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

/// Frames between the driver and the pyramid thread: decoded and rectified.
struct Loaded {
  std::int64_t t_ns = 0;
  Clock::time_point released;
  bool readable = false;
  tracking::StereoFrame frame;
  double ms = 0.0;
};

/// Two frames of look-ahead per queue: enough to keep both cores busy, small
/// enough that a real-time run drops rather than lags.
constexpr std::size_t kQueueCapacity = 2;

/// A frame's left image as read from the sequence, and the time reading it took.
struct Decoded {
  std::optional<cv::Mat> left;  ///< nullopt: unreadable
  double ms = 0.0;
};

Decoded decode(io::Sequence& sequence, std::size_t i) {
  const auto t0 = Clock::now();
  Decoded d;
  d.left = sequence.leftImage(i);
  d.ms = msSince(t0);
  return d;
}

Loaded load(io::Sequence& sequence, std::size_t i, Decoded decoded, const camera::StereoRectifier& rect,
            Clock::time_point released) {
  const auto t0 = Clock::now();
  Loaded item;
  item.t_ns = sequence.frameTime(i);
  item.released = released;
  if (decoded.left) {
    item.readable = true;
    item.frame.t_ns = item.t_ns;
    item.frame.left = rect.rectify(0, *decoded.left);
    // Decoded by the tracking thread if the frame becomes a keyframe.
    item.frame.right = tracking::LazyImage([&rect, raw = sequence.rightImageLoader(i)] {
      const cv::Mat image = raw();
      return image.empty() ? cv::Mat() : rect.rectify(1, image);
    });
  }
  item.ms = decoded.ms + msSince(t0);
  return item;
}

/// The driver thread's work: loads the frames in order until they end or
/// the queue is closed (the consumer stopped). Real time: each frame is
/// released at its timestamp and dropped when the queue is full; its image
/// is read from its file before then, as a camera hands over pixels at their
/// timestamp (rectification and all after it count in the latency).
/// Offline: released when the driver gets to it, and waits for room.
void readFrames(io::Sequence& sequence, const std::vector<std::size_t>& frames, const camera::StereoRectifier& rect,
                bool realtime, BoundedQueue<Loaded>& loaded, std::atomic<std::size_t>& dropped) {
  const auto start = Clock::now();
  for (const std::size_t i : frames) {
    Decoded decoded = decode(sequence, i);
    Clock::time_point released = Clock::now();
    if (realtime) {
      released = start + std::chrono::nanoseconds(sequence.frameTime(i) - sequence.frameTime(frames.front()));
      if (loaded.closedBy(released)) return;
    }
    Loaded item = load(sequence, i, std::move(decoded), rect, released);
    if (!realtime) {
      if (!loaded.push(std::move(item))) return;
    } else if (!loaded.tryPush(std::move(item))) {
      ++dropped;
    }
  }
}

/// The pyramid thread's work: each loaded frame's edge pyramid, until the
/// loaded frames end or the prepared queue is closed.
void prepareFrames(BoundedQueue<Loaded>& loaded, BoundedQueue<PipelineFrame>& prepared, const camera::StereoRectifier& rect,
                   const vision::VisionOptions& vision, const std::atomic<std::size_t>& dropped) {
  while (std::optional<Loaded> item = loaded.pop()) {
    const auto t0 = Clock::now();
    PipelineFrame p;
    p.t_ns = item->t_ns;
    p.released = item->released;
    p.readable = item->readable;
    if (item->readable) p.frame = tracking::prepareFrame(item->frame, rect, vision);
    p.load_ms = item->ms + msSince(t0);
    p.dropped_before = dropped;
    if (!prepared.push(std::move(p))) return;
  }
}

}  // namespace

void nameThread(const char* name) { pthread_setname_np(pthread_self(), name); }

PipelineResult runThreaded(io::Sequence& sequence, const std::vector<std::size_t>& frames,
                           const camera::StereoRectifier& rect, const vision::VisionOptions& vision, bool realtime,
                           const std::function<void(PipelineFrame)>& consume) {
  BoundedQueue<Loaded> loaded(kQueueCapacity);
  BoundedQueue<PipelineFrame> prepared(kQueueCapacity);
  std::exception_ptr driver_error, prepare_error;
  std::atomic<std::size_t> dropped{0};
  std::thread driver([&] {
    nameThread("ev-read");
    try {
      readFrames(sequence, frames, rect, realtime, loaded, dropped);
    } catch (...) {
      driver_error = std::current_exception();
    }
    loaded.close();
  });
  std::thread preparer([&] {
    nameThread("ev-pyramid");
    try {
      prepareFrames(loaded, prepared, rect, vision, dropped);
    } catch (...) {
      prepare_error = std::current_exception();
      loaded.close();
    }
    prepared.close();
  });
  // Whatever happens below, the threads are stopped and joined.
  const auto stop = [&] {
    loaded.close();
    prepared.close();
    if (driver.joinable()) driver.join();
    if (preparer.joinable()) preparer.join();
  };
  try {
    while (std::optional<PipelineFrame> item = prepared.pop()) consume(std::move(*item));
  } catch (...) {
    stop();
    throw;
  }
  stop();
  if (driver_error) std::rethrow_exception(driver_error);
  if (prepare_error) std::rethrow_exception(prepare_error);
  return {dropped};
}

}  // namespace edgevio::pipeline
