#pragma once
// What a rank will hold at its peak, known before it is spent: each method's measured bytes per
// unique triangle and fixed base (runs/distribute/memory_model.csv, the landscape at 1 and 3.8 M
// triangles, rounded up), and what cutting the scene into regions holds beside it. Every rank
// checks its estimate against the memory it may use (usableMemoryBytes: its share of the
// machine's memory, ulimit -v) before it loads or keeps triangles, and refuses with the estimate.
#include <cstdint>
#include <string>

#include "src/core/system.hpp"

namespace lzb::regions {

// The peak of `method` holding `triangles` unique triangles, frame buffers excluded; with
// compactBvh (`--bvh compact`), Embree's compact leaves for the methods that build its BVH.
uint64_t methodPeakBytes(const std::string& method, uint64_t triangles, bool compactBvh = false);
// `--bvh` (fast | compact): whether Embree's leaves are compact; InputError naming `where` for
// anything else.
bool parseCompactBvh(const std::string& value, const std::string& where);
// Whether `method` has a measured model (every registered method must).
bool hasMemoryModel(const std::string& method);

// What a streamed cut holds while it deals the regions: the world centre and the part index of
// each of the scene's `triangles` (src/regions/streamed_share.hpp).
uint64_t streamedCutBytes(uint64_t triangles);

// Throws InputError "<scene>: <what> needs an estimated N MiB, more than the M MiB this process
// may use (its share of physical memory, ulimit -v)<hint>" when `bytes` exceed `usable` (by
// default usableMemoryBytes() now).
void requireEstimate(uint64_t bytes, const std::string& scene, const std::string& what,
                     const std::string& hint = "", uint64_t usable = usableMemoryBytes());

}  // namespace lzb::regions
