#include "src/core/system.hpp"

#include <malloc.h>
#include <omp.h>
#include <sched.h>
#include <sys/resource.h>
#include <unistd.h>

#include <algorithm>
#include <climits>
#include <cstdlib>
#include <fstream>
#include <optional>
#include <string>

#include "src/core/error.hpp"

namespace lzb {

int coresOwned() {
  cpu_set_t set;
  if (sched_getaffinity(0, sizeof(set), &set) == 0) return CPU_COUNT(&set) > 0 ? CPU_COUNT(&set) : 1;
  return omp_get_num_procs();
}

uint64_t peakMemoryBytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return uint64_t(usage.ru_maxrss) * 1024;  // Linux reports kilobytes
}

bool keepFreedMemory() {
  // glibc's largest mmap threshold on 64-bit (HEAP_MAX_SIZE / 2): smaller blocks come from the
  // heap, and a trim threshold of 2 GiB leaves the heap's free top where it is.
  constexpr int kMmapThreshold = 32 << 20;
  return mallopt(M_MMAP_THRESHOLD, kMmapThreshold) == 1 &&
         mallopt(M_TRIM_THRESHOLD, INT_MAX) == 1;
}

namespace {

// RLIMIT_AS (ulimit -v) in bytes, or nullopt when there is none.
std::optional<uint64_t> addressSpaceLimit() {
  rlimit limit{};
  if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return uint64_t(limit.rlim_cur);
}

}  // namespace

bool oneArenaUnderAddressLimit() {
  if (!addressSpaceLimit()) return false;
  // glibc reserves 64 MiB of address space for each thread's own arena, untouched but counted
  // by ulimit -v: one heap for every thread (2 x 1 hybrid ranks: 300 instead of 430 MiB mapped
  // before the scene, runs/distribute/README.md).
  return mallopt(M_ARENA_MAX, 1) == 1;
}

void useThreads(int threads) {
  omp_set_num_threads(threads);
  // llvmpipe reads this when its screen is created; keeps ranks from oversubscribing cores.
  setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
}

namespace {

uint64_t physicalMemoryBytes() {
  const long pages = sysconf(_SC_PHYS_PAGES), size = sysconf(_SC_PAGESIZE);
  return pages > 0 && size > 0 ? uint64_t(pages) * uint64_t(size) : ~uint64_t(0);
}

// Address space mapped now (VmSize in /proc/self/status), 0 when unknown.
uint64_t mappedBytes() {
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmSize:", 0) == 0) return std::strtoull(line.c_str() + 7, nullptr, 10) * 1024;
  return 0;
}

// What RLIMIT_AS leaves of the address space for the estimates (unlimited: all of it): the
// limit less what is mapped now and less what a run maps beyond what it touches (thread stacks,
// Embree's and llvmpipe's reservations), which the estimates of resident memory leave out.
uint64_t addressSpaceLeft() {
  constexpr uint64_t kUntouchedReserve = uint64_t(256) << 20;
  const std::optional<uint64_t> limit = addressSpaceLimit();
  if (!limit) return ~uint64_t(0);
  const uint64_t taken = mappedBytes() + kUntouchedReserve;
  return *limit > taken ? *limit - taken : 0;
}

std::string mib(uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20); }

int processesOnMachine = 1;

}  // namespace

void setProcessesOnMachine(int processes) {
  processesOnMachine = std::max(processes, 1);
}

uint64_t usableMemoryBytes() {
  return std::min(physicalMemoryBytes() / uint64_t(processesOnMachine), addressSpaceLeft());
}

std::string memoryShortfall(uint64_t bytes, uint64_t usable) {
  return mib(bytes) + " MiB, more than the " + mib(usable) +
         " MiB this process may use (its share of physical memory, ulimit -v)";
}

void requireMemory(uint64_t bytes, const std::string& where, const std::string& what) {
  const uint64_t usable = usableMemoryBytes();
  if (bytes <= usable) return;
  throw InputError(where + ": " + what + " needs " + memoryShortfall(bytes, usable));
}

}  // namespace lzb
