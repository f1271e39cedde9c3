#pragma once
// The three threads of METHOD.md §1 joined by bounded queues: the driver
// reads and rectifies each stereo frame, the second thread builds its edge
// pyramid, and the calling thread consumes it (tracking and estimation).
// Offline the queues block and every frame reaches the consumer in order, so
// the result does not depend on thread timing. In real time the driver
// releases frames at their timestamps and drops (counts) those the pipeline
// has no room for; the stage code is the same.
#include <chrono>
#include <cstdint>
#include <functional>
#include <vector>

#include "edgevio/camera/stereo_rectifier.h"
#include "edgevio/io/sequence.h"
#include "edgevio/tracking/edge_tracker.h"

namespace edgevio::pipeline {

/// A frame as it reaches the consumer.
struct PipelineFrame {
  std::int64_t t_ns = 0;
  std::chrono::steady_clock::time_point released;  ///< when the frame arrived (real time: at its timestamp)
  bool readable = false;  ///< false: its left image did not decode (the frame carries nothing else)
  tracking::PreparedFrame frame;
  double load_ms = 0.0;   ///< decoding, rectification and the pyramid, on the first two threads
  std::size_t dropped_before = 0;  ///< real time: frames dropped so far
};

struct PipelineResult {
  std::size_t dropped = 0;  ///< real time: frames the pipeline had no room for
};

/// Names the calling thread (at most 15 characters) as profilers (perf,
/// top -H) and debuggers show it.
void nameThread(const char* name);

/// Runs `frames` (indices into `sequence`, increasing) through the threads;
/// `consume` is called on this thread, in order. Exceptions of any stage are
/// rethrown here after every thread has stopped.
PipelineResult runThreaded(io::Sequence& sequence, const std::vector<std::size_t>& frames,
                           const camera::StereoRectifier& rectifier, const vision::VisionOptions& vision, bool realtime,
                           const std::function<void(PipelineFrame)>& consume);

}  // namespace edgevio::pipeline
