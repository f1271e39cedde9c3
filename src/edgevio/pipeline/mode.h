#pragma once
// The system's four settings (METHOD.md §7): the IMU on or off, loop closure
// on or off. Named as the paper names them: edge-only, edge+loop, edge+imu,
// edge+imu+loop (the full system).
#include <optional>
#include <string>

namespace edgevio::pipeline {

struct Mode {
  bool imu = true;
  bool loop = true;
};

inline bool operator==(const Mode& a, const Mode& b) { return a.imu == b.imu && a.loop == b.loop; }

/// "edge-only" | "edge+loop" | "edge+imu" | "edge+imu+loop".
std::string modeName(Mode mode);
/// The mode of a name; nullopt for anything else.
std::optional<Mode> parseMode(const std::string& name);
/// The valid names, for messages.
inline const char* kModeNames = "edge-only, edge+loop, edge+imu or edge+imu+loop";

}  // namespace edgevio::pipeline
