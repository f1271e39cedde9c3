#pragma once
// Progress lines for long runs: shown on a terminal (frames, rate, ETA),
// silent in a pipe or CI log so logs stay clean.
#include <chrono>
#include <cstddef>
#include <string>

namespace edgevio::cli {

class Progress {
 public:
  /// `what` names the unit ("frames"); `enabled` is usually isatty(stderr).
  Progress(std::string what, bool enabled);
  static bool stderrIsTerminal();
  /// Redraws at most every 0.2 s; `done == total` finishes the line.
  void update(std::size_t done, std::size_t total, double sequence_seconds_done = -1.0);

 private:
  std::string what_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_, last_;
};

}  // namespace edgevio::cli
