#pragma once
// Time is int64 nanoseconds everywhere (METHOD.md §2); these are the one
// conversion to and from seconds.
#include <cmath>
#include <cstdint>

namespace edgevio {

/// A time or duration in nanoseconds as seconds.
inline double toSeconds(std::int64_t ns) { return static_cast<double>(ns) * 1e-9; }

/// Seconds as the nearest nanosecond.
inline std::int64_t toNanoseconds(double s) { return static_cast<std::int64_t>(std::llround(s * 1e9)); }

}  // namespace edgevio
