#pragma once
// The readers of user files, each as a function of the file's bytes: the
// fuzz targets. A target may finish or throw InputError (a bad input named
// and explained); anything else (another exception, a crash, a sanitizer
// report, a read past the bytes) is a bug. The same targets run under
// libFuzzer (scripts/fuzz.sh, a clang build) and, on seeds and their
// systematic mutations, in the unit tests (fuzz_targets_test.cpp).
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace edgevio::fuzz {

using Bytes = std::vector<std::uint8_t>;

struct FuzzTarget {
  const char* name;
  const char* reads;  ///< what the bytes are read as
  /// Reads the bytes; throws InputError when they are not a valid file of the kind.
  void (*read)(const std::uint8_t* data, std::size_t size);
  /// Well-formed inputs, built in code: what fuzzing starts from. Each is read without an error.
  std::vector<Bytes> (*seeds)();
};

const std::vector<FuzzTarget>& fuzzTargets();
/// The target of a name; throws std::invalid_argument naming the targets when there is none.
const FuzzTarget& fuzzTarget(const std::string& name);
/// One input through a target: true when read, false when rejected with an
/// InputError; any other exception passes through (a bug).
bool readOrReject(const FuzzTarget& target, const std::uint8_t* data, std::size_t size);

}  // namespace edgevio::fuzz
