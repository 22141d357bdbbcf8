#include "src/sampletree/sampletree_renderer.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "mpi/decomposition.hpp"
#include "src/core/error.hpp"
#include "src/core/timer.hpp"
#include "src/sampletree/approximated_pixels.hpp"
#include "src/sampletree/traversal.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/sampletree/tree_store.hpp"
#include "src/splat/splatter.hpp"

namespace lzb::sampletree {

namespace {

// The splats of `nodes`, each its representative triangle's centroid in camera space.
template <bool kWide, bool kPixel>
uint64_t splatNodes(const SampleTree& tree, const std::vector<uint32_t>& nodes,
                    const Camera& camera, const SplatSetup& setup, KeyBuffer& keys) {
  PointSplatter<kWide, kPixel> splatter(setup, keys);
  for (uint32_t i : nodes) {
    const TreeNode& n = tree.nodes[i];
    const glm::dvec3 d = glm::dvec3(n.representativePoint[0], n.representativePoint[1],
                                    n.representativePoint[2]) - camera.position();
    splatter.add(float(glm::dot(d, camera.right())), float(glm::dot(d, camera.up())),
                 float(glm::dot(d, camera.forward())), n.representativeId);
  }
  splatter.flush();
  return splatter.splatted();
}

// What this rank prefetches: below the stops inside the preorder span of its share (the nodes
// near its own; every rank traverses alike, so the shares of the next frame lie close by).
std::vector<uint32_t> prefetchOfShare(const SampleTree& tree, const Traversal& walk,
                                      const std::vector<uint32_t>& splats,
                                      const std::vector<uint32_t>& drawn, int levels) {
  uint32_t lo = UINT32_MAX, hi = 0;
  for (const auto* list : {&splats, &drawn})
    if (!list->empty()) lo = std::min(lo, list->front()), hi = std::max(hi, list->back());
  std::vector<uint32_t> mine;
  for (uint32_t s : walk.stops)
    if (s >= lo && s <= hi) mine.push_back(s);
  return belowStops(tree, mine, levels);
}

// A render rank's share when the link's last rank serves nodes: rank r of the size - 1 others.
WorkShare renderShare(const WorkShare& share, const NodeLink& link) {
  if (share.size != link.group().size || share.rank != link.group().rank)
    throw std::logic_error("sampletree: the node server's ranks differ from the frame's");
  return WorkShare{share.rank, share.size - 1};
}

}  // namespace

SampleTreeRenderer::SampleTreeRenderer(const Scene& scene, const RenderOptions& options,
                                       const SampleTreeOptions& st)
    : scene_(scene), options_(options), st_(st) {
  Stopwatch clock;
  if (st.treePath.empty()) {
    tree_ = buildTree(scene, TreeParams{st.c, options.seed, st.leafTriangles}, options.threads);
    setup_.addStage("build_tree", clock.lap());
  } else if (st.nodeServer) {
    openNodeServer();
    setup_.addStage("read_node_table", clock.lap());
  } else if (st.cacheMb > 0.0) {
    openStore();
    setup_.addStage("read_node_table", clock.lap());
  } else {
    tree_ = readTree(st.treePath);
    setup_.addStage("read_tree", clock.lap());
  }
  if (!source_) treeTriangles_ = tree_.triangles(), treeBytes_ = storeBytes(tree_);
  if (!st.treePath.empty())
    require(tree().sceneTriangles == scene.expandedTriangles(), st.treePath + " (sample tree store)",
            "built from a scene of " + std::to_string(tree().sceneTriangles) +
                " expanded triangles, but " + scene.source + " has " +
                std::to_string(scene.expandedTriangles()));
  // The construction's own c and seed: a store's, whatever --c and --seed say.
  setup_.setShared("tree_c", tree().params.c);
  setup_.setShared("tree_seed", double(tree().params.seed));
  setup_.setShared("tree_nodes", double(tree().nodes.size()));
  setup_.setShared("tree_triangles", double(treeTriangles_));
  setup_.setShared("tree_bytes", double(treeBytes_));
}

// Out of core: the node table resident, a cache within --cache-mb for the triangles.
void SampleTreeRenderer::openStore() {
  store_ = std::make_unique<StoreReader>(st_.treePath);
  source_ = store_.get();
  treeTriangles_ = store_->triangles();
  treeBytes_ = store_->fileBytes();
  checkBudget();
  cache_ = std::make_unique<NodeCache>(*store_, cacheBudget());
}

// With a node server: the last rank opens the store and serves; the others receive its node table
// and load through it. Every check below sees the same table on every rank, so a refusal is
// agreed on alike.
void SampleTreeRenderer::openNodeServer() {
  require(options_.frameGroups == 1, "--node-server",
          "one rank serves the nodes to the ranks of one frame; it cannot be combined with "
          "--frame-groups " + std::to_string(options_.frameGroups));
  link_ = std::make_unique<NodeLink>();
  if (link_->serving()) {
    server_ = std::make_unique<NodeServer>(*link_, st_.treePath);
    source_ = &server_->store();
    treeTriangles_ = server_->store().triangles();
    treeBytes_ = server_->store().fileBytes();
  } else {
    client_ = std::make_unique<NodeClient>(*link_);
    source_ = client_.get();
    treeTriangles_ = client_->triangles();
    treeBytes_ = client_->fileBytes();
  }
  checkBudget();
  if (client_) cache_ = std::make_unique<NodeCache>(*client_, cacheBudget());
}

uint64_t SampleTreeRenderer::cacheBudget() const { return uint64_t(st_.cacheMb * 1024.0 * 1024.0); }

// Streaming needs each node whole in the cache: a smaller budget can never draw the largest.
void SampleTreeRenderer::checkBudget() {
  const uint64_t budget = cacheBudget();
  uint64_t largest = 0;
  for (const TreeNode& n : source_->table().nodes) largest = std::max(largest, cachedBytes(n));
  require(largest <= budget, "--cache-mb",
          "a node cache of " + std::to_string(budget) + " bytes cannot hold the largest node of " +
              st_.treePath + " (" + std::to_string(largest) +
              " bytes of triangles and bookkeeping; at least " +
              std::to_string(std::ceil(double(largest) / 1048576.0 * 1e6) / 1e6) + " MiB)");
  setup_.setShared("cache_budget_bytes", double(budget));
  setup_.setShared("largest_node_bytes", double(largest));
}

std::string SampleTreeRenderer::decomposition() const {
  const std::string split =
      "the tree traversal on every rank; the visited nodes, in preorder, dealt to ranks as "
      "contiguous runs of equal cost (a node's triangles, 1 per splat); each rank draws its "
      "nodes' triangles (native z-buffer) and splats into one key buffer; depth compositing "
      "by (depth, id)";
  if (!link_) return split;
  return "node server: the last rank reads the store and serves node payloads to the others, "
         "which render: " + split;
}

void SampleTreeRenderer::render(const Camera& camera, int frame, const WorkShare& rankShare,
                                Framebuffer& fb, FrameStats& stats) {
  if (server_) return serveFrame(stats);
  Frame f;
  f.camera = &camera;
  // With a node server the render ranks split the frame among themselves.
  f.share = link_ ? renderShare(rankShare, *link_) : rankShare;
  Stopwatch clock;
  f.tree = &tree();
  if (cache_) cache_->beginFrame();
  traverseAndDeal(f);
  prefetchBelow(f);
  stats.addStage("traverse", clock.lap());
  splat(f, fb);
  stats.addStage("splat", clock.lap());
  drawTriangles(f, fb, stats);
  stats.addStage("triangles", clock.lap());
  shading_.shade(camera, scene_.light, fb, options_.threads);
  stats.addStage("shade", clock.lap());
  stats.setShared("approximated_pixels",
                  double(approximatedPixels(*f.tree, f.walk.stops, camera,
                                            st_.stopDraw == StopDraw::kSplat ? st_.splat : 0,
                                            options_.threads)));
  stats.addStage("approximated", clock.lap());
  report(f, stats);
  if (client_) {
    stats.addCount("remote_wait_seconds", client_->takeWaitSeconds());
    client_->frameDrawn(frame);
  }
}

// Every rank traverses alike; this rank keeps its run of the visits, dealt by cost.
void SampleTreeRenderer::traverseAndDeal(Frame& f) const {
  const SampleTree& tree = *f.tree;
  f.walk = traverse(tree, *f.camera, st_.splat, st_.stopDraw, options_.threads);
  std::vector<double> costs;
  costs.reserve(f.walk.visits.size());
  for (const Visit& v : f.walk.visits)
    costs.push_back(v.splat ? 1.0 : double(tree.nodes[v.node].triangleCount));
  for (uint32_t k : dealByCost(costs, f.share)) {
    const Visit& v = f.walk.visits[k];
    const TreeNode& n = tree.nodes[v.node];
    if (v.splat) {
      f.splats.push_back(v.node);
    } else {
      f.ranges.push_back({n.firstTriangle, n.firstTriangle + n.triangleCount});
      f.drawn.push_back(v.node);
      f.triangles += n.triangleCount;
    }
  }
}

// Out of core: the nodes below this rank's stops, loaded in the background for the next frames.
void SampleTreeRenderer::prefetchBelow(const Frame& f) {
  if (!cache_ || st_.cacheLevels <= 0) return;
  cache_->touch(f.drawn);  // the prefetch, running from now on, must not evict them
  cache_->prefetch(prefetchOfShare(*f.tree, f.walk, f.splats, f.drawn, st_.cacheLevels));
}

// The splats into the key buffer, resolved into fb.
void SampleTreeRenderer::splat(Frame& f, Framebuffer& fb) {
  const Camera& camera = *f.camera;
  keys_.reset(camera.width(), camera.height(), scene_.expandedTriangles() > 0xffffffffull,
              options_.threads);
  const SplatSetup setup = SplatSetup::from(camera, st_.splat);
  shading_.begin();
  shading_.addRepresentatives(*f.tree, f.splats);
  f.splatted = withSplatter(keys_, st_.splat, [&]<bool kWide, bool kPixel>() {
    return splatNodes<kWide, kPixel>(*f.tree, f.splats, camera, setup, keys_);
  });
  keys_.resolve(fb, options_.threads);
}

// The native z-buffer keeps the nearer (depth, ID) against the splats already in fb.
void SampleTreeRenderer::drawTriangles(const Frame& f, Framebuffer& fb, FrameStats& stats) {
  if (cache_) {
    stats.addCount("draw_batches",
                   double(drawPaged(*cache_, *f.tree, f.drawn, *f.camera, options_.threads, raster_,
                                    staging_, shading_, fb)));
    return;
  }
  raster_.drawSoup(*f.camera, TriangleSoup{tree_.positions, tree_.ids, f.ranges}, options_.threads,
                   fb);
  shading_.keepShown(fb, {tree_.positions, tree_.ids, tree_.colours, f.ranges}, options_.threads);
}

void SampleTreeRenderer::report(const Frame& f, FrameStats& stats) {
  stats.setShared("nodes_visited", double(f.walk.visited));
  stats.setShared("nodes_stopped", double(f.walk.stops.size()));
  stats.setShared("subtrees_culled", double(f.walk.culled));
  stats.setShared("tree_bytes", double(treeBytes_));
  stats.addCount("nodes_drawn", double(f.ranges.size()));
  stats.addCount("triangles_drawn", double(f.triangles));
  stats.addCount("splats_drawn", double(f.splats.size()));
  stats.addCount("splats_in_image", double(f.splatted));
  if (cache_) reportCache(stats);
}

// The server's frame: it draws nothing and waits until every render rank has drawn its share,
// then reports what it served meanwhile.
void SampleTreeRenderer::serveFrame(FrameStats& stats) {
  Stopwatch clock;
  const ServerCounters c = server_->awaitFrame();
  stats.addStage("serve", clock.lap());
  stats.addCount("served_requests", double(c.requests));
  stats.addCount("served_nodes", double(c.nodes));
  stats.addCount("served_bytes", double(c.bytes));
  stats.addCount("file_bytes_read", double(c.fileBytesRead));
}

// Per rank, summed in the report: what the cache did since the last frame's report (prefetch
// loads finishing between frames count in the next frame).
void SampleTreeRenderer::reportCache(FrameStats& stats) {
  cache_->check();  // a damaged block met by the prefetch fails this frame
  const CacheCounters c = cache_->takeCounters();
  stats.addCount("nodes_loaded", double(c.nodesLoaded));
  stats.addCount("nodes_prefetched", double(c.nodesPrefetched));
  stats.addCount("bytes_read", double(c.bytesRead));
  stats.addCount("file_bytes_read", double(c.fileBytesRead));
  stats.addCount("cache_hits", double(c.hits));
  stats.addCount("nodes_evicted", double(c.evicted));
  stats.addCount("load_wait_seconds", c.waitSeconds);
  stats.addCount("cache_bytes", double(cache_->residentBytes()));
}

}  // namespace lzb::sampletree
