#pragma once
// The k-d cut of region_cut.hpp over units spread over the ranks of a group, no rank holding
// them all: each rank holds a run of consecutive units of one triangle each (its triangles, by
// ID: the units' index, the cut's tie order). Every level of the cut takes its boxes by
// all-reduced minima and maxima, and finds each node's cut unit by a radix select over the units'
// (coordinate, index) keys, 8 bits a round, each round's counts all-reduced (16 rounds a level,
// O(units) work a rank), so the regions are those splitIntoRegions gives over all the units, bit
// for bit, on any number of ranks.
#include <cstdint>
#include <glm/glm.hpp>
#include <span>
#include <vector>

#include "mpi/group.hpp"
#include "src/regions/region_cut.hpp"

namespace lzb::regions {

// Each local unit's region, as splitIntoRegions(all centres in index order, {}, regions) gives
// it. Collective over `group`. Local unit u is unit firstIndex + u of them all, at centres[u].
std::vector<uint32_t> splitIntoRegionsTogether(const mpi::Group& group,
                                               std::span<const glm::dvec3> centres,
                                               uint64_t firstIndex, uint32_t regions);

// The cut of the local units and every region's triangles over all ranks (collective).
RegionCut cutIntoRegionsTogether(const mpi::Group& group, std::span<const glm::dvec3> centres,
                                 uint64_t firstIndex, uint32_t regions);

}  // namespace lzb::regions
