#pragma once
// The live side of the viewer: the page with an empty run, served by a
// LiveServer, and each frame's record as the event the page appends
// (view/viewer.html: {row, position, picture}; at the end {summary}).
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "edgevio/pipeline/frame_record.h"
#include "edgevio/pipeline/run_summary.h"
#include "edgevio/view/live_server.h"

namespace edgevio::view {

class LiveView {
 public:
  /// Serves the page on 127.0.0.1:port (0: a free port); `title` names the run (mode, sequence).
  LiveView(int port, const std::string& mode, const std::string& sequence);
  int port() const { return server_.port(); }
  void frame(const pipeline::FrameRecord& record, const std::vector<std::uint8_t>& jpeg);
  /// Sends the run's summary and the end of the stream.
  void finish(const pipeline::RunSummary& summary);

 private:
  LiveServer server_;
};

}  // namespace edgevio::view
