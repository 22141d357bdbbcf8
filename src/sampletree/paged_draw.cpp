#include "src/sampletree/paged_draw.hpp"

#include <stdexcept>

namespace lzb::sampletree {

namespace {

// The staging copy and the rasterizer's bins grow with a batch: past this many triangles a frame
// is drawn in several, so its memory beyond the cache stays bounded whatever it draws.
constexpr uint64_t kBatchTriangles = uint64_t(1) << 20;

// The longest run of nodes from `begin` whose payloads fit `budget` together, of at most
// kBatchTriangles triangles (one node at least).
size_t batchEnd(const SampleTree& table, std::span<const uint32_t> nodes, size_t begin,
                uint64_t budget) {
  uint64_t bytes = 0, triangles = 0;
  size_t end = begin;
  while (end < nodes.size() && bytes + cachedBytes(table.nodes[nodes[end]]) <= budget &&
         (end == begin || triangles + table.nodes[nodes[end]].triangleCount <= kBatchTriangles)) {
    bytes += cachedBytes(table.nodes[nodes[end]]);
    triangles += table.nodes[nodes[end++]].triangleCount;
  }
  if (end == begin) throw std::logic_error("drawPaged: a node larger than the cache budget");
  return end;
}

void stage(const std::vector<const NodePayload*>& payloads, SoupStaging& s) {
  s.positions.clear();
  s.ids.clear();
  s.colours.clear();
  for (const NodePayload* p : payloads) {
    s.positions.insert(s.positions.end(), p->positions.begin(), p->positions.end());
    s.ids.insert(s.ids.end(), p->ids.begin(), p->ids.end());
    s.colours.insert(s.colours.end(), p->colours.begin(), p->colours.end());
  }
}

}  // namespace

uint64_t drawPaged(NodeCache& cache, const SampleTree& table, std::span<const uint32_t> nodes,
                   const Camera& camera, int threads, NativeRasterizer& raster,
                   SoupStaging& staging, TreeShading& shading, Framebuffer& fb) {
  uint64_t batches = 0;
  const std::vector<uint32_t> order = cache.residentFirst(nodes);  // keys: any order, one image
  nodes = order;
  for (size_t begin = 0; begin < nodes.size(); ++batches) {
    const size_t end = batchEnd(table, nodes, begin, cache.budget());
    const std::span<const uint32_t> batch = nodes.subspan(begin, end - begin);
    stage(cache.acquire(batch), staging);
    const SoupRange all{0, staging.ids.size()};
    raster.drawSoup(camera, TriangleSoup{staging.positions, staging.ids, {&all, 1}}, threads, fb);
    shading.keepShown(fb, {staging.positions, staging.ids, staging.colours, {&all, 1}}, threads);
    cache.release(batch);
    begin = end;
  }
  return batches;
}

}  // namespace lzb::sampletree
