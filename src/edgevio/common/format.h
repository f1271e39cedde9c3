#pragma once
// printf-style formatting into a std::string; the compiler checks each
// call's arguments against its pattern (-Wformat).
#include <string>

namespace edgevio {

/// The text printf(pattern, ...) would print.
std::string formatText(const char* pattern, ...) __attribute__((format(printf, 1, 2)));

}  // namespace edgevio
