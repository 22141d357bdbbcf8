#pragma once
// Facts about the running process: cores it may use, peak memory.
#include <cstdint>
#include <string>

namespace lzb {

int coresOwned();             // CPUs in this process's affinity mask (what mpirun bound it to)
uint64_t peakMemoryBytes();   // peak resident set size so far
// Keeps freed heap blocks (up to 32 MiB each) in the process instead of returning them to the
// kernel: every frame allocates and frees the same buffers, and glibc's default unmaps or trims
// them, so each frame faults their pages in again. False when the allocator refused (e.g. under
// AddressSanitizer). Call once at start.
bool keepFreedMemory();
// Under an address-space limit (ulimit -v), every thread allocates from one heap: glibc's
// per-thread arenas each map 64 MiB they may never touch. True when it applied. Call once at
// start, before threads are made.
bool oneArenaUnderAddressLimit();
// Sets the thread count for OpenMP and (through LP_NUM_THREADS) llvmpipe; call before rendering.
void useThreads(int threads);

// The processes of this job on this machine (MPI ranks on one node), which share its physical
// memory; 1 until set (once, at start).
void setProcessesOnMachine(int processes);
// Bytes this process may still allocate: the least of its share of physical memory and what the
// address-space limit (RLIMIT_AS, `ulimit -v`) leaves above the address space already mapped.
uint64_t usableMemoryBytes();
// Throws InputError "<where>: <what> needs N MiB, more than the M MiB this process may use
// (its share of physical memory, ulimit -v)" when `bytes` exceed usableMemoryBytes(). Call
// before allocating.
void requireMemory(uint64_t bytes, const std::string& where, const std::string& what);
// The words of a refusal after "needs": "N MiB, more than the M MiB this process may use (its
// share of physical memory, ulimit -v)".
std::string memoryShortfall(uint64_t bytes, uint64_t usable);

}  // namespace lzb
