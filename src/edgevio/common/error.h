#pragma once
// Errors about input the user gave us. Library code never exits or aborts on bad
// input: it throws InputError, whose message names the file, the line (when
// there is one), what was wrong and what was expected. The CLI prints it and
// exits with status 1.
#include <cstddef>
#include <stdexcept>
#include <string>

namespace edgevio {

class InputError : public std::runtime_error {
 public:
  /// line = 0 means "the file as a whole".
  InputError(const std::string& file, std::size_t line, const std::string& what);
  explicit InputError(const std::string& what) : std::runtime_error(what) {}
};

}  // namespace edgevio
