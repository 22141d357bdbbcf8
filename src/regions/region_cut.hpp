#pragma once
// The scene's regions under --distribute data: the k-d cut of the scene's units into regions
// balanced by triangle count, and the deal of the regions to ranks. Both depend on the units and
// the region count alone, never on the rank count, so the image does not either; only who holds
// which region changes. Free of MPI and of the scene model, so that they are unit tested alone.
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "src/core/renderer.hpp"

namespace lzb::regions {

// `asked` (--regions), or when it is 0 the default from the scene's size alone (never the rank
// count), at least 16 and at most 4096: one per 2^16 unique triangles held as one part
// (`onePart`: an exact method), one per 2^20 held a part per region (each region then costs a
// renderer's whole frame pass: runs/distribute/README.md).
uint32_t regionCount(uint32_t asked, uint64_t uniqueTriangles, bool onePart);

// Cuts units (pieces of the scene that go whole to one region, at world position centres[u],
// costing triangles[u], or 1 each when triangles is empty) into `regions` regions: a k-d split
// that halves the region count at each step along the widest axis of its units' centres, at the
// point where the triangles before it match the regions before it. Ties break by unit index, so
// the result depends on the units and `regions` alone. Returns each unit's region in
// [0, regions); a region may stay empty when there are fewer units than regions.
std::vector<uint32_t> splitIntoRegions(std::span<const glm::dvec3> centres,
                                       std::span<const uint64_t> triangles, uint32_t regions);

// The regions rank share.rank holds, given each region's triangles: in the k-d order, each
// region to the rank holding the fewest triangles so far (the first such rank). Equal regions go
// round-robin, so neighbours in space land on different ranks and a view's cost spreads over
// them, as interleaved screen tiles do (a rank holding a cluster of neighbours did most of the
// frame whenever the camera stood among them); uneven ones still balance.
std::vector<uint32_t> regionsOfRank(std::span<const uint64_t> regionTriangles,
                                    const WorkShare& share);
// The rank of `ranks` holding each region (the same deal).
std::vector<int> regionOwners(std::span<const uint64_t> regionTriangles, int ranks);

// The cut of a scene's units and what it weighs.
struct RegionCut {
  std::vector<uint32_t> regionOf;         // each unit's region
  std::vector<uint64_t> regionTriangles;  // each region's triangles
};
// splitIntoRegions with each region's triangles summed.
RegionCut cutIntoRegions(std::span<const glm::dvec3> centres, std::span<const uint64_t> triangles,
                         uint32_t regions);

// The triangles each of `ranks` ranks holds when the regions are dealt by regionsOfRank.
std::vector<uint64_t> trianglesPerRank(std::span<const uint64_t> regionTriangles, int ranks);

}  // namespace lzb::regions
