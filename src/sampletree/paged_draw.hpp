#pragma once
// Drawing a frame's triangles from the node cache (out of core): in batches whose payloads fit
// the cache's budget and hold at most 2^20 triangles (one batch when a frame's nodes fit both),
// each acquired (loading what is missing, waiting for it), copied into one triangle soup, drawn
// by the native z-buffer and released. The z-buffer keeps the nearer (depth, ID) at each pixel whatever the order, so any
// batching gives the image of one draw of them all, i.e. the in-core renderer's. The nodes the
// cache holds are drawn first: a frame larger than the cache then reuses what the last one left
// (in preorder every frame, each batch would evict the nodes the next frame starts with).
#include <cstdint>
#include <span>
#include <vector>

#include "src/core/camera.hpp"
#include "src/core/framebuffer.hpp"
#include "src/sampletree/node_cache.hpp"
#include "src/sampletree/tree_shading.hpp"
#include "src/zbuffer/native_raster.hpp"

namespace lzb::sampletree {

// The soup a batch is copied into, kept between frames.
struct SoupStaging {
  std::vector<glm::vec3> positions;
  std::vector<uint64_t> ids;
  std::vector<Rgba8> colours;
};

// nodes: each with triangles and its cached bytes (cachedBytes) within the cache's budget. After
// each batch, `shading` keeps the inputs of the batch's triangles fb shows (tree_shading.hpp).
// Returns the number of batches drawn.
uint64_t drawPaged(NodeCache& cache, const SampleTree& table, std::span<const uint32_t> nodes,
                   const Camera& camera, int threads, NativeRasterizer& raster,
                   SoupStaging& staging, TreeShading& shading, Framebuffer& fb);

}  // namespace lzb::sampletree
