#include "edgevio/cli/progress.h"

#include <unistd.h>

#include <cstdio>

namespace edgevio::cli {

Progress::Progress(std::string what, bool enabled)
    : what_(std::move(what)), enabled_(enabled), start_(std::chrono::steady_clock::now()), last_(start_) {}

bool Progress::stderrIsTerminal() { return ::isatty(STDERR_FILENO) == 1; }

void Progress::update(std::size_t done, std::size_t total, double sequence_seconds_done) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (done < total && std::chrono::duration<double>(now - last_).count() < 0.2) return;
  last_ = now;
  const double elapsed = std::chrono::duration<double>(now - start_).count();
  const double rate = elapsed > 0 ? static_cast<double>(done) / elapsed : 0.0;
  const double eta = rate > 0 ? static_cast<double>(total - done) / rate : 0.0;
  std::fprintf(stderr, "\r%zu/%zu %s  %.1f/s", done, total, what_.c_str(), rate);
  if (sequence_seconds_done >= 0 && elapsed > 0) std::fprintf(stderr, "  %.1fx real time", sequence_seconds_done / elapsed);
  std::fprintf(stderr, "  ETA %.0f s   ", eta);
  if (done >= total) std::fprintf(stderr, "\n");
  std::fflush(stderr);
}

}  // namespace edgevio::cli
