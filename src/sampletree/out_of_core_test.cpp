// Rendering out of core (section 6.2): the node cache's frames equal the in-core renderer's for
// any cache size (streaming when a frame does not fit), a block corrupted after opening is an
// InputError naming the store at render time, and the cache's counters add up.
#include <gtest/gtest.h>

#include <atomic>
#include <cstring>
#include <filesystem>
#include <span>
#include <fstream>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/sampletree/node_cache.hpp"
#include "src/sampletree/sampletree_renderer.hpp"
#include "src/sampletree/store_reader.hpp"
#include "src/sampletree/store_format.hpp"
#include "src/sampletree/traversal.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/sampletree/tree_store.hpp"
#include "src/scene/load.hpp"
#include "tests/support/cameras.hpp"
#include "tests/support/frames.hpp"
#include "tests/support/render.hpp"

namespace lzb::sampletree {
namespace {

namespace fs = std::filesystem;
constexpr int kW = 160, kH = 120;

const Scene& flake() {
  static const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  return scene;
}

// The scene's tree in a store (leaves of 8 triangles: many nodes, several blocks).
const fs::path& store() {
  static const fs::path p = [] {
    const fs::path dir = fs::temp_directory_path() / "lzb_out_of_core_test";
    fs::create_directories(dir);
    const fs::path file = dir / "flake.lzbtree";
    writeTree(buildTree(flake(), TreeParams{13.8, 5, 8}, 2), file.string());
    return file;
  }();
  return p;
}

// Cameras approaching the scene and turning: the frames of a walkthrough.
std::vector<Camera> walk() {
  const Bounds b = flake().bounds();
  const double d = b.diagonal();
  std::vector<Camera> out;
  for (double k : {6.0, 2.5, 1.2, 0.8, 0.8})
    out.push_back(test::lookAtCamera(b.center() + glm::dvec3(0.3, 0.5, 1.0) * (k * d),
                                     b.center() + glm::dvec3(0.05 * k * d, 0, 0), 0.01 * d, 20 * d,
                                     kW, kH));
  return out;
}

SampleTreeOptions options(double cacheBytes, int splat = 1, int levels = 1) {
  SampleTreeOptions st;
  st.treePath = store().string();
  st.splat = splat;
  st.cacheMb = cacheBytes / (1024.0 * 1024.0);  // exact: a power-of-two division
  st.cacheLevels = levels;
  return st;
}

SampleTreeRenderer makeRenderer(const SampleTreeOptions& st, int threads = 2) {
  RenderOptions o;
  o.threads = threads;
  return SampleTreeRenderer(flake(), o, st);
}

struct Frame {
  Framebuffer fb{kW, kH};
  FrameStats stats;
  double count(const char* name) const { return stats.counts.value(name, 0.0); }
};

// A frame and its statistics (the store's counts are read per frame).
Frame frameOf(SampleTreeRenderer& r, const Camera& camera, WorkShare share = {}) {
  Frame f;
  f.fb = test::renderFrame(r, camera, &f.stats, share);
  return f;
}

uint64_t largestNode() {
  uint64_t largest = 0;
  for (const TreeNode& n : readTree(store().string()).nodes)
    largest = std::max(largest, cachedBytes(n));
  return largest;
}

// Payload bytes of the nodes a frame draws triangles of (1 rank).
uint64_t framePayload(const SampleTree& tree, const Camera& camera, int splat) {
  uint64_t bytes = 0;
  for (const Visit& v : traverse(tree, camera, splat).visits)
    if (!v.splat) bytes += cachedBytes(tree.nodes[v.node]);
  return bytes;
}

TEST(OutOfCore, FramesEqualTheInCoreRendererForEveryCacheSize) {
  const std::vector<Camera> cameras = walk();
  const SampleTree whole = readTree(store().string());
  uint64_t biggestFrame = 0;
  for (const Camera& c : cameras) biggestFrame = std::max(biggestFrame, framePayload(whole, c, 1));
  const uint64_t largest = largestNode();
  ASSERT_GT(biggestFrame, 3 * largest) << "the scene must not fit the smallest cache in one batch";
  for (int splat : {1, 3}) {
    SampleTreeOptions inCore = options(0, splat);
    inCore.cacheMb = 0.0;
    SampleTreeRenderer reference = makeRenderer(inCore);
    ASSERT_EQ(reference.cache(), nullptr);
    for (uint64_t budget : {uint64_t(64) << 20, biggestFrame / 2, largest}) {
      SampleTreeRenderer paged = makeRenderer(options(double(budget), splat, 2));
      ASSERT_NE(paged.cache(), nullptr);
      double batches = 0;
      for (size_t k = 0; k < cameras.size(); ++k) {
        const Frame want = frameOf(reference, cameras[k]);
        const Frame got = frameOf(paged, cameras[k]);
        EXPECT_TRUE(test::sameKeys(want.fb, got.fb))
            << "splat " << splat << ", budget " << budget << ", frame " << k;
        EXPECT_EQ(got.count("triangles_drawn"), want.count("triangles_drawn"));
        EXPECT_LE(got.count("cache_bytes"), double(budget));
        batches = std::max(batches, got.count("draw_batches"));
      }
      if (budget == largest) {
        EXPECT_GT(batches, 1.0) << "the smallest cache streams the frame";
      }
      if (budget == uint64_t(64) << 20) {
        EXPECT_EQ(batches, 1.0);
      }
    }
  }
}

TEST(OutOfCore, RankSharesCompositeToTheOneRankImage) {
  const Camera camera = walk()[2];
  SampleTreeRenderer one = makeRenderer(options(double(largestNode())), 1);
  const Frame all = frameOf(one, camera);
  Framebuffer composite(kW, kH);
  composite.clear();
  for (int rank = 0; rank < 3; ++rank) {
    SampleTreeRenderer part = makeRenderer(options(double(largestNode())), 1);
    compositeNearer(composite, frameOf(part, camera, WorkShare{rank, 3}).fb);
  }
  EXPECT_TRUE(test::sameKeys(all.fb, composite));
}

// A source that counts what the cache asks of it (a node server answers each call with one message).
class CountingSource : public NodeSource {
 public:
  explicit CountingSource(StoreReader& store) : store_(store) {}
  const SampleTree& table() const override { return store_.table(); }
  std::vector<NodePayload> readNodes(std::span<const uint32_t> nodes) override {
    ++calls;
    asked += nodes.size();
    return store_.readNodes(nodes);
  }
  uint64_t fileBytesRead() const override { return store_.fileBytesRead(); }
  std::atomic<uint64_t> calls{0}, asked{0};

 private:
  StoreReader& store_;
};

// The missing nodes of one acquire reach the source in one call, each once, as the store reads
// them; resident nodes are not asked for again.
TEST(OutOfCore, OneAcquireAsksTheSourceOnce) {
  StoreReader reader(store().string());
  CountingSource source(reader);
  NodeCache cache(source, 64 << 20);
  std::vector<uint32_t> nodes;
  for (uint32_t n = 0; n < reader.table().nodes.size() && nodes.size() < 300; n += 2)
    if (reader.table().nodes[n].triangleCount > 0) nodes.push_back(n);
  ASSERT_EQ(nodes.size(), 300u);
  cache.beginFrame();
  const std::vector<const NodePayload*> got = cache.acquire(nodes);
  EXPECT_EQ(source.calls.load(), 1u);
  EXPECT_EQ(source.asked.load(), nodes.size());
  for (size_t k = 0; k < nodes.size(); k += 37) {
    const NodePayload want = reader.read(nodes[k]);
    EXPECT_EQ(got[k]->ids, want.ids) << "node " << nodes[k];
    EXPECT_EQ(got[k]->positions, want.positions) << "node " << nodes[k];
  }
  cache.release(nodes);
  cache.acquire(nodes);
  cache.release(nodes);
  EXPECT_EQ(source.calls.load(), 1u);
  EXPECT_EQ(cache.takeCounters().hits, nodes.size());
}

TEST(OutOfCore, CountersAddUpAndASecondFrameLoadsNothing) {
  const Camera camera = walk()[2];
  SampleTreeRenderer r = makeRenderer(options(64 << 20, 1, 0));
  const Frame first = frameOf(r, camera);
  uint64_t payload = 0, cached = 0;  // bytes read; what the cache counts (with bookkeeping)
  const SampleTree& table = r.tree();
  for (const Visit& v : traverse(table, camera, 1).visits)
    if (!v.splat)
      payload += payloadBytes(table.nodes[v.node]), cached += cachedBytes(table.nodes[v.node]);
  EXPECT_GT(first.count("nodes_loaded"), 10.0);
  EXPECT_EQ(first.count("nodes_loaded"), first.count("nodes_drawn"));
  EXPECT_EQ(first.count("bytes_read"), double(payload));
  EXPECT_EQ(first.count("bytes_read"), 48.0 * first.count("triangles_drawn"));
  EXPECT_GT(first.count("file_bytes_read"), 0.0);
  EXPECT_EQ(first.count("cache_hits"), 0.0);
  EXPECT_EQ(first.count("nodes_prefetched"), 0.0);
  EXPECT_EQ(first.count("cache_bytes"), double(cached));
  const Frame second = frameOf(r, camera);
  EXPECT_EQ(second.count("nodes_loaded"), 0.0);
  EXPECT_EQ(second.count("bytes_read"), 0.0);
  EXPECT_EQ(second.count("file_bytes_read"), 0.0);
  EXPECT_EQ(second.count("cache_hits"), first.count("nodes_drawn"));
  EXPECT_EQ(second.count("load_wait_seconds"), 0.0);
  EXPECT_TRUE(test::sameKeys(first.fb, second.fb));
}

// A frame three times the cache streams in batches, in the same order every frame: the next
// frame finds the nodes the cache kept (LRU evicted each just before it was needed again: 0 hits).
TEST(OutOfCore, AFrameLargerThanTheCacheKeepsPartOfItForTheNext) {
  const Camera camera = walk()[3];
  const uint64_t payload = framePayload(readTree(store().string()), camera, 1);
  const uint64_t budget = std::max(payload / 3, 2 * largestNode());
  ASSERT_LT(budget, payload);
  SampleTreeRenderer r = makeRenderer(options(double(budget), 1, 0));
  const Frame first = frameOf(r, camera);
  const Frame second = frameOf(r, camera);
  EXPECT_GT(first.count("draw_batches"), 1.0);
  EXPECT_TRUE(test::sameKeys(first.fb, second.fb));
  // At least half of what fits beside one batch is reused.
  const double drawn = second.count("nodes_drawn");
  EXPECT_GT(second.count("cache_hits"), 0.15 * drawn) << "of " << drawn << " nodes";
  EXPECT_EQ(second.count("cache_hits") + second.count("nodes_loaded"), drawn);
}

TEST(OutOfCore, PrefetchLoadsWhatTheNextFrameNeeds) {
  const std::vector<Camera> cameras = walk();
  double hits[3] = {0, 0, 0};
  for (int levels : {0, 1, 2}) {
    SampleTreeRenderer r = makeRenderer(options(64 << 20, 1, levels));
    const Frame far = frameOf(r, cameras[1]);
    r.cache()->drain();  // what the frame queued is loaded
    const CacheCounters between = r.cache()->takeCounters();
    EXPECT_EQ(far.count("nodes_prefetched") + double(between.nodesPrefetched) > 0, levels > 0);
    const Frame near = frameOf(r, cameras[2]);
    hits[levels] = near.count("cache_hits");
    const double demanded = near.count("nodes_loaded") - near.count("nodes_prefetched");
    if (levels == 0)
      EXPECT_EQ(demanded + near.count("cache_hits"), near.count("nodes_drawn"));
    else
      EXPECT_LE(demanded + near.count("cache_hits"), near.count("nodes_drawn"));
    // The same frame again: everything resident, nothing loaded.
    r.cache()->drain();
    r.cache()->takeCounters();
    EXPECT_EQ(frameOf(r, cameras[2]).count("nodes_loaded"), 0.0) << levels;
  }
  EXPECT_GT(hits[1], hits[0]);
  EXPECT_GE(hits[2], hits[1]);
}

TEST(OutOfCore, ACacheSmallerThanTheLargestNodeIsRefused) {
  try {
    makeRenderer(options(double(largestNode() - 1)));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--cache-mb"), std::string::npos) << e.what();
  }
}

// A byte of the IDs of a node the frame draws, in a block after the node table's: the store
// opens, the frame fails naming the store.
TEST(OutOfCore, ABlockCorruptedAfterOpeningFailsTheFrame) {
  const fs::path bad = store().parent_path() / "corrupt.lzbtree";
  fs::copy_file(store(), bad, fs::copy_options::overwrite_existing);
  const SampleTree whole = readTree(bad.string());
  const Camera camera = walk()[2];
  const format::Sections s = format::sections(whole.nodes.size(), whole.triangles());
  const uint64_t tableBlock = (whole.nodes.size() * sizeof(TreeNode) - 1) / kStoreBlock;
  uint64_t at = 0;
  for (const Visit& v : traverse(whole, camera, 1).visits) {
    const uint64_t offset = s.ids + whole.nodes[v.node].firstTriangle * 8;
    if (!v.splat && offset / kStoreBlock > tableBlock) at = offset;
  }
  ASSERT_GT(at, 0u);
  {
    std::fstream f(bad, std::ios::binary | std::ios::in | std::ios::out);
    f.seekg(std::streamoff(kStoreHeaderBytes + at));
    const char c = char(f.get() ^ 0x40);
    f.seekp(std::streamoff(kStoreHeaderBytes + at));
    f.put(c);
  }
  SampleTreeOptions st = options(64 << 20);
  st.treePath = bad.string();
  SampleTreeRenderer r = makeRenderer(st);  // header, table and node table are sound
  try {
    frameOf(r, camera);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(bad.string()), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("corrupted"), std::string::npos) << e.what();
  }
  // The loader stopped: the next frame fails alike.
  EXPECT_THROW(frameOf(r, camera), InputError);
}

}  // namespace
}  // namespace lzb::sampletree
