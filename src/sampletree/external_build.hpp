#pragma once
// External construction of a sample tree (section 5.1) for scenes larger than memory: the input
// is streamed several times instead of held. A bounds pass fixes the root cube; counting passes
// (cell_census.hpp) find |P(u)| of the cells down to buckets, subtrees whose triangles fit the
// budget; a writing pass appends every triangle to its bucket's part of a scratch file
// (spill_file.hpp); each bucket is then built, sampled and laid out in memory by the in-memory
// build's own code, keeping its root's triangles for the levels above; those top levels are
// sampled last, and the store is written section by section from the scratch files.
//
// The split rule, the drawing order and the Philox keys depend only on a cell and its triangles
// in input order, so the store is byte for byte the one the in-memory build writes (tested).
#include <cstdint>
#include <filesystem>
#include <string>

#include "src/sampletree/sample_tree.hpp"
#include "src/sampletree/triangle_stream.hpp"

namespace lzb::sampletree {

// Bytes the in-memory build holds per triangle (measured peak: ~170 on builtin:landscape, 4.8 M
// triangles, input, areas, octree lists and the laid-out tree), rounded up.
constexpr uint64_t kBuildBytesPerTriangle = 200;

struct ExternalOptions {
  uint64_t bucketTriangles = 0;  // the most triangles a bucket may hold
  uint64_t bufferTriangles = 0;  // triangles the writing pass buffers before it flushes
  uint64_t topTriangles = 0;     // the most triangles the top levels may hold
  std::filesystem::path scratchDir;  // where the scratch files go (created, removed after)
  bool progress = false;
};
// The options a memory budget gives: 60 % for the buckets built at once (one per thread), 15 % for
// the write buffers, 10 % for the top levels, the rest for the census, the read-ahead and the copy
// buffers. Throws InputError naming --mem-mb when a bucket could not hold more than a leaf.
ExternalOptions optionsForMemory(uint64_t memBytes, const TreeParams& params, int threads);

struct ExternalReport {
  uint64_t triangles = 0, nodes = 0;
  uint64_t buckets = 0, topCells = 0, largestBucket = 0;
  uint64_t topTriangles = 0;  // triangles held by the top levels (their cells' borders)
  int streamPasses = 0;       // reads of the input: bounds, counting, writing (when needed)
  int countingPasses = 0;     // the last also spills, unless the input's IDs were out of order
  uint64_t spillBytes = 0, storeBytes = 0;
  // Wall seconds: reading the input (every pass: bounds, counting, writing to the scratch file),
  // building the buckets, sampling the top levels and writing the store.
  double inputSeconds = 0.0, bucketSeconds = 0.0, storeSeconds = 0.0;
};

// Builds the tree of `in` and writes the store to `out` (atomically).
ExternalReport buildTreeExternal(const TriangleStream& in, const TreeParams& params,
                                 const ExternalOptions& options, int threads,
                                 const std::string& out);

}  // namespace lzb::sampletree
