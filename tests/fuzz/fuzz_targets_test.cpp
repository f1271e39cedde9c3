// The fuzz targets on their seeds and on systematic mutations of them:
// every truncation, single bytes overwritten with 0x00, 0xff and the byte
// with its top bit flipped, 32-bit fields overwritten with extreme lengths,
// and a fixed-seed random mix of those, plus every input a fuzzer found a bug
// with (tests/fuzz/regressions/<target>/). Each must be read or rejected
// with an InputError; under the sanitizer build, without a report.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <ostream>
#include <string>

#include "common/test_support.h"
#include "fuzz/fuzz_targets.h"

namespace edgevio::fuzz {
namespace {

/// Positions to mutate: all of a short input, else `count` evenly spaced ones.
std::vector<std::size_t> positions(std::size_t size, std::size_t count) {
  std::vector<std::size_t> p;
  if (size <= count) {
    for (std::size_t i = 0; i < size; ++i) p.push_back(i);
  } else {
    for (std::size_t k = 0; k < count; ++k) p.push_back(k * size / count);
  }
  return p;
}

std::vector<Bytes> mutations(const Bytes& seed) {
  std::vector<Bytes> out;
  for (std::size_t n : positions(seed.size(), 400)) out.emplace_back(seed.begin(), seed.begin() + static_cast<std::ptrdiff_t>(n));
  for (std::size_t i : positions(seed.size(), 400)) {
    for (std::uint8_t value : {std::uint8_t{0x00}, std::uint8_t{0xff}, static_cast<std::uint8_t>(seed[i] ^ 0x80)}) {
      Bytes m = seed;
      m[i] = value;
      out.push_back(m);
    }
  }
  // Lengths, counts and offsets of the binary formats are 32-bit little-endian fields.
  for (std::size_t i : positions(seed.size() >= 4 ? seed.size() - 3 : 0, 300)) {
    for (std::uint32_t value : {0xffffffffu, 0x7fffffffu, 0x80000000u, 0x00010000u}) {
      Bytes m = seed;
      for (int b = 0; b < 4; ++b) m[i + b] = static_cast<std::uint8_t>(value >> (8 * b));
      out.push_back(m);
    }
  }
  std::mt19937 random(7);
  for (int k = 0; k < 300 && !seed.empty(); ++k) {
    Bytes m = seed;
    const int changes = 1 + static_cast<int>(random() % 4);
    for (int c = 0; c < changes; ++c) m[random() % m.size()] = static_cast<std::uint8_t>(random());
    if (random() % 2 == 0) m.resize(random() % (m.size() + 1));
    out.push_back(m);
  }
  return out;
}

std::string hex(const Bytes& b) {
  static const char digits[] = "0123456789abcdef";
  std::string s;
  for (std::size_t i = 0; i < std::min<std::size_t>(b.size(), 64); ++i) {
    s += digits[b[i] >> 4];
    s += digits[b[i] & 15];
  }
  return s + (b.size() > 64 ? "..." : "") + " (" + std::to_string(b.size()) + " bytes)";
}

class FuzzTargets : public ::testing::TestWithParam<FuzzTarget> {};

}  // namespace

// The target's name in test listings (not its bytes).
void PrintTo(const FuzzTarget& t, std::ostream* os) { *os << t.name; }

namespace {

TEST_P(FuzzTargets, SeedsAreReadWithoutError) {
  const FuzzTarget& t = GetParam();
  const std::vector<Bytes> seeds = t.seeds();
  ASSERT_FALSE(seeds.empty());
  for (const Bytes& seed : seeds) EXPECT_TRUE(readOrReject(t, seed.data(), seed.size())) << t.name << ": " << hex(seed);
}

TEST_P(FuzzTargets, MutatedSeedsAreReadOrRejectedWithAnInputError) {
  const FuzzTarget& t = GetParam();
  std::size_t inputs = 0, read = 0;
  for (const Bytes& seed : t.seeds()) {
    for (const Bytes& m : mutations(seed)) {
      try {
        read += readOrReject(t, m.data(), m.size());
      } catch (const std::exception& e) {
        ADD_FAILURE() << t.name << ": " << e.what() << " on " << hex(m);
      }
      ++inputs;
    }
  }
  // Both answers occur: the mutations reach past the first check.
  EXPECT_GT(read, 0u);
  EXPECT_LT(read, inputs);
  std::printf("%s: %zu inputs, %zu read, %zu rejected\n", t.name, inputs, read, inputs - read);
}

TEST_P(FuzzTargets, InputsAFuzzerFoundABugWithAreHandled) {
  const FuzzTarget& t = GetParam();
  const std::filesystem::path dir = std::filesystem::path(test::sourceDir()) / "tests/fuzz/regressions" / t.name;
  if (!std::filesystem::is_directory(dir)) GTEST_SKIP() << "none for " << t.name << " (" << dir << ")";
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path(), std::ios::binary);
    const Bytes input(std::istreambuf_iterator<char>(in), {});
    try {
      readOrReject(t, input.data(), input.size());
    } catch (const std::exception& e) {
      ADD_FAILURE() << entry.path() << ": " << e.what();
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Readers, FuzzTargets, ::testing::ValuesIn(fuzzTargets()),
                         [](const ::testing::TestParamInfo<FuzzTarget>& p) { return std::string(p.param.name); });

}  // namespace
}  // namespace edgevio::fuzz
