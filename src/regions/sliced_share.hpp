#pragma once
// --distribute data from a binary PLY file read in slices (src/scene/ply_slices.hpp), so that no
// rank reads, parses or holds the whole file (the PUML pattern):
//  1. each of the group's N ranks reads 1/N of the vertex records and 1/N of the face records;
//  2. it fetches the vertices its faces use from the ranks that read them (MPI_Alltoallv) and
//     makes its faces' triangles as the loader does (the stored frame from the all-reduced
//     bounds; IDs from an exclusive scan of the kept counts, dropped triangles included);
//  3. the regions are cut from the spread centres (distributed_cut.hpp) and dealt as every share
//     is (partOfRank), so they are the streamed share's;
//  4. each triangle travels to the rank holding its region, packed round by round into messages
//     of at most `chunkBytes` a pair and kExchangeRoundBytes a rank (counts are 32-bit, and what
//     leaves is never held whole), and the exchange's buffers are freed before the rank builds
//     anything on its share.
// The share, its IDs and the outline are those holdStreamedShare gives (tested on 1 to 4 ranks);
// nothing per triangle or vertex of the whole scene is held by any rank.
#include <cstdint>
#include <functional>
#include <optional>
#include <string>

#include "mpi/group.hpp"
#include "src/core/scene_outline.hpp"
#include "src/regions/share.hpp"

namespace lzb::regions {

// The most bytes one rank sends another in one round of the exchange, and sends in all in one
// round (what it packs at once).
constexpr uint64_t kExchangeChunkBytes = uint64_t(1) << 30;
constexpr uint64_t kExchangeRoundBytes = uint64_t(16) << 20;

// Bytes a rank holds at the load's peak per face it reads (face records, triangles, centres, the
// cut's keys and the exchange's records), for the refusal before reading.
constexpr uint64_t kSlicedLoadBytesPerFace = 160;
// What a rank of `ranks` holds at the load's peak reading its slice of `faces` faces, besides
// the process's base.
uint64_t slicedLoadBytes(uint64_t faces, int ranks);
// The faces of the file `path` when --distribute data reads it in slices (its header alone read:
// a record found other than a triangle still sends it to the stream), else nullopt.
std::optional<uint64_t> slicedFaces(const std::string& path);

// This rank's share of the PLY file `path` read in slices by the ranks of `group` (its frame
// group), cut into `regions` regions (0: the default) in parts of `layout`; nullopt when the file
// is not read in slices (not a binary PLY of triangles in records of one size: the ranks agree),
// and the caller streams or loads it. Collective. beforeKeeping(held) runs once the regions are
// dealt, before any triangle travels. A rank that fails alone (a malformed record in its slice, a
// share refused) fails every rank alike (mpi::agree): one message, every rank's JobFailed.
std::optional<HeldShare> holdSlicedShare(
    const std::string& path, const mpi::Group& group, uint32_t regions, Parts layout, bool quiet,
    SceneOutline& outline, const std::function<void(const HeldShare&)>& beforeKeeping = {},
    uint64_t chunkBytes = kExchangeChunkBytes);

}  // namespace lzb::regions
