#pragma once
// Deterministic random numbers for the simulator. The standard library's
// distributions are implementation-defined, so the same seed could give other
// numbers with another compiler; these are exact everywhere.
#include <cmath>
#include <cstdint>

namespace edgevio::sim {

/// SplitMix64 (Steele, Lea, Flood 2014): a fast, well-mixed 64-bit generator.
inline std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ULL;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ULL;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBULL;
  return x ^ (x >> 31);
}

/// Hash of several integers (a counter-based generator: noise for pixel i of
/// frame k is hash(seed, k, i), whatever the thread that computes it).
inline std::uint64_t hashCombine(std::uint64_t a, std::uint64_t b) { return splitmix64(a ^ (splitmix64(b) + 0x632BE59BD9B4E019ULL)); }

class Rng {
 public:
  explicit Rng(std::uint64_t seed) : state_(splitmix64(seed)) {}
  std::uint64_t next() { return state_ = splitmix64(state_); }
  /// Uniform in [0, 1).
  double uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  int integer(int lo, int hi_inclusive) { return lo + static_cast<int>(next() % static_cast<std::uint64_t>(hi_inclusive - lo + 1)); }
  /// Standard normal by Box-Muller.
  double gaussian() {
    const double u1 = 1.0 - uniform(), u2 = uniform();
    return std::sqrt(-2.0 * std::log(u1)) * std::cos(6.283185307179586 * u2);
  }

 private:
  std::uint64_t state_;
};

}  // namespace edgevio::sim
