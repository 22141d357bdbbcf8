#include "src/core/system.hpp"

#include <sched.h>
#include <sys/resource.h>

#include <cstdlib>
#include <string>

#include <omp.h>

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

void useThreads(int threads) {
  omp_set_num_threads(threads);
  // llvmpipe reads this when its screen is created; keeps ranks from oversubscribing cores.
  setenv("LP_NUM_THREADS", std::to_string(threads).c_str(), 1);
}

}  // namespace lzb
