// libFuzzer's entry to the targets of fuzz_targets.h (scripts/fuzz.sh builds
// and runs it). The environment chooses: EDGEVIO_FUZZ_TARGET=NAME the target
// (`list`: print their names and exit); EDGEVIO_FUZZ_SEEDS=DIR writes the
// target's seeds to DIR first, so that DIR can be the corpus it starts from.
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "fuzz/fuzz_targets.h"

namespace {

const edgevio::fuzz::FuzzTarget* chosen = nullptr;

const edgevio::fuzz::FuzzTarget& target() { return *chosen; }

}  // namespace

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  const char* name = std::getenv("EDGEVIO_FUZZ_TARGET");
  if (name != nullptr && std::string(name) == "list") {
    for (const edgevio::fuzz::FuzzTarget& t : edgevio::fuzz::fuzzTargets()) std::printf("%s\t%s\n", t.name, t.reads);
    std::exit(0);
  }
  try {
    chosen = &edgevio::fuzz::fuzzTarget(name != nullptr ? name : "");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "EDGEVIO_FUZZ_TARGET: %s\n", e.what());
    std::exit(2);
  }
  if (const char* dir = std::getenv("EDGEVIO_FUZZ_SEEDS")) {
    std::filesystem::create_directories(dir);
    int i = 0;
    for (const edgevio::fuzz::Bytes& seed : target().seeds()) {
      std::ofstream out(std::string(dir) + "/seed" + std::to_string(i++), std::ios::binary);
      out.write(reinterpret_cast<const char*>(seed.data()), static_cast<std::streamsize>(seed.size()));
    }
  }
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  edgevio::fuzz::readOrReject(target(), data, size);
  return 0;
}
