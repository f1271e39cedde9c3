// keepFreedMemory: a large block freed and allocated again is not faulted in
// again page by page.
#include "edgevio/common/process_memory.h"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <cstdlib>

namespace edgevio {
namespace {

long minorFaults() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_minflt;
}

TEST(ProcessMemory, AFreedBlockIsReusedWithoutPageFaults) {
  if (!keepFreedMemory()) GTEST_SKIP() << "the allocator has no such settings here (not glibc, or a sanitizer's)";
  // Above glibc's largest dynamic mmap threshold (32 MiB): by default every
  // allocation of it is a fresh mapping, every page of it a fault when touched.
  constexpr std::size_t kBytes = 48u << 20, kPage = 4096, kPages = kBytes / kPage;
  void* (*volatile allocate)(std::size_t) = std::malloc;  // volatile: the pair must not be optimised away
  void (*volatile release)(void*) = std::free;
  long faults_after_first = 0;
  for (int cycle = 0; cycle < 4; ++cycle) {
    const long before = minorFaults();
    auto* block = static_cast<volatile char*>(allocate(kBytes));
    ASSERT_NE(block, nullptr);
    for (std::size_t i = 0; i < kBytes; i += kPage) block[i] = static_cast<char>(i);
    release(const_cast<char*>(block));
    if (cycle > 0) faults_after_first += minorFaults() - before;
  }
  // Three reuses touch 3·12288 pages; fresh mappings would fault on each.
  EXPECT_LT(faults_after_first, static_cast<long>(kPages) / 10);
}

}  // namespace
}  // namespace edgevio
