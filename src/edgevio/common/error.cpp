#include "edgevio/common/error.h"

namespace edgevio {

namespace {
std::string locate(const std::string& file, std::size_t line, const std::string& what) {
  std::string s = file;
  if (line > 0) s += ":" + std::to_string(line);
  return s + ": " + what;
}
}  // namespace

InputError::InputError(const std::string& file, std::size_t line, const std::string& what)
    : std::runtime_error(locate(file, line, what)) {}

}  // namespace edgevio
