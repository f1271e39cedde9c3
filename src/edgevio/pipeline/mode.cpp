#include "edgevio/pipeline/mode.h"

namespace edgevio::pipeline {

std::string modeName(Mode mode) {
  return std::string("edge") + (mode.imu ? "+imu" : "") + (mode.loop ? "+loop" : "") + (mode.imu || mode.loop ? "" : "-only");
}

std::optional<Mode> parseMode(const std::string& name) {
  for (const bool imu : {false, true})
    for (const bool loop : {false, true})
      if (modeName({imu, loop}) == name) return Mode{imu, loop};
  return std::nullopt;
}

}  // namespace edgevio::pipeline
