#pragma once
// Facts about the running process: cores it may use, peak memory.
#include <cstdint>

namespace lzb {

int coresOwned();             // CPUs in this process's affinity mask (what mpirun bound it to)
uint64_t peakMemoryBytes();   // peak resident set size so far
// Sets the thread count for OpenMP and (through LP_NUM_THREADS) llvmpipe; call before rendering.
void useThreads(int threads);

}  // namespace lzb
