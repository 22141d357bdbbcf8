#include "src/core/system.hpp"

#include <malloc.h>
#include <sys/resource.h>

#include <cstddef>
#include <cstdlib>

#include <gtest/gtest.h>

namespace lzb {
namespace {

long minorFaults() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_minflt;
}

// Allocates 16 MiB, writes one byte a page and frees it: what a frame does with its buffers.
void allocateTouchFree() {
  constexpr size_t kBytes = size_t(16) << 20;
  volatile char* p = static_cast<char*>(std::malloc(kBytes));
  ASSERT_NE(p, nullptr);
  for (size_t i = 0; i < kBytes; i += 4096) p[i] = 1;
  std::free(const_cast<char*>(p));
}

// Faults of the second of two allocate-touch-free rounds.
long faultsOfReuse() {
  allocateTouchFree();  // the first time the pages fault in
  const long before = minorFaults();
  allocateTouchFree();
  return minorFaults() - before;
}

TEST(System, KeepFreedMemoryReusesABlockWithoutFaultingItsPagesAgain) {
#if defined(__SANITIZE_ADDRESS__)
  GTEST_SKIP() << "AddressSanitizer's allocator does not take mallopt";
#endif
  // An allocator that maps large blocks and trims at once faults every page on every reuse
  // (4096 on 4 KiB pages) ...
  ASSERT_EQ(mallopt(M_TRIM_THRESHOLD, 0), 1);
  ASSERT_EQ(mallopt(M_MMAP_THRESHOLD, 4096), 1);
  EXPECT_GE(faultsOfReuse(), 1000);
  // ... kept, the block faults none.
  ASSERT_TRUE(keepFreedMemory());
  EXPECT_LT(faultsOfReuse(), 64);
}

}  // namespace
}  // namespace lzb
