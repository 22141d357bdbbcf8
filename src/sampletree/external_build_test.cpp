// The external construction writes, byte for byte, the store the in-memory build writes, over
// several counting passes, many buckets and triangles that stay in the top levels; it cleans up its
// scratch files and refuses budgets that cannot hold a bucket.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/sampletree/external_build.hpp"
#include "tests/support/files.hpp"
#include "src/sampletree/tree_build.hpp"
#include "src/sampletree/tree_store.hpp"
#include "src/scene/builtin.hpp"
#include "src/scene/load.hpp"

namespace lzb::sampletree {
namespace {

namespace fs = std::filesystem;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "lzb_external_build_test" / name;
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// The in-memory store of `scene`, and the external one of `stream` with buckets of at most
// `bucket` triangles; both files' bytes.
struct TwoStores {
  std::vector<char> inMemory, external;
  ExternalReport report;
};
TwoStores buildBoth(const Scene& scene, const TriangleStream& stream, const TreeParams& params,
               uint64_t bucket, const fs::path& dir) {
  writeTree(buildTree(scene, params, 2), (dir / "memory.lzbtree").string());
  ExternalOptions o;
  o.bucketTriangles = bucket;
  o.bufferTriangles = 3000;  // many flushes: a bucket's triangles come back from many chunks
  o.topTriangles = 1 << 20;
  o.scratchDir = dir;
  TwoStores p;
  p.report = buildTreeExternal(stream, params, o, 2, (dir / "external.lzbtree").string());
  p.inMemory = test::fileBytes(dir / "memory.lzbtree");
  p.external = test::fileBytes(dir / "external.lzbtree");
  return p;
}

TEST(ExternalBuild, StreamedLandscapeGivesTheInMemoryStore) {
  const std::string spec = "landscape?objects=3000&seed=4";
  const Scene scene = loadScene("builtin:" + spec, true);
  const auto chunks = builtinChunks(spec);
  ASSERT_TRUE(chunks.has_value());
  SceneOutline base;
  base.source = "builtin:" + spec;
  base.camera = chunks->camera;
  const MeshChunkStream stream(base, chunks->triangles, chunks->generate,
                               MeshChunkStream::Kind::kGenerator);
  const fs::path dir = scratch("landscape");
  const TwoStores p = buildBoth(scene, stream, TreeParams{13.8, 3, 32}, 200, dir);
  EXPECT_EQ(p.report.triangles, scene.expandedTriangles());
  EXPECT_GT(p.report.buckets, 500u);
  EXPECT_GT(p.report.topCells, 10u);
  EXPECT_GT(p.report.topTriangles, 0u);  // sampled into the top levels and staying on borders
  EXPECT_GE(p.report.countingPasses, 2);  // the last one spills: no writing pass follows
  EXPECT_EQ(p.report.streamPasses, 1 + p.report.countingPasses);
  EXPECT_LE(p.report.largestBucket, 200u);
  ASSERT_EQ(p.external.size(), p.inMemory.size());
  EXPECT_TRUE(p.external == p.inMemory);
  // Only the two stores are left: the scratch folder went.
  EXPECT_EQ(std::distance(fs::directory_iterator(dir), fs::directory_iterator()), 2);
}

TEST(ExternalBuild, InstancedSceneAndOtherParametersGiveTheInMemoryStore) {
  const Scene scene = loadScene("builtin:sphereflake?depth=2", true);
  const SceneStream stream(scene);
  for (const TreeParams params : {TreeParams{0.5, 9, 8}, TreeParams{13.8, 1, 64}}) {
    const fs::path dir = scratch("sphereflake");
    const TwoStores p = buildBoth(scene, stream, params, 300, dir);
    EXPECT_GT(p.report.buckets, 5u);
    ASSERT_EQ(p.external.size(), p.inMemory.size()) << params.c;
    EXPECT_TRUE(p.external == p.inMemory) << params.c;
  }
}

TEST(ExternalBuild, OneBucketHoldingEverythingIsTheInMemoryBuild) {
  const Scene scene = loadScene("builtin:sphereflake?depth=1", true);
  const fs::path dir = scratch("onebucket");
  const TwoStores p = buildBoth(scene, SceneStream(scene), TreeParams{}, 1 << 20, dir);
  EXPECT_EQ(p.report.buckets, 1u);
  EXPECT_EQ(p.report.topCells, 0u);
  EXPECT_TRUE(p.external == p.inMemory);
}

TEST(ExternalBuild, MemoryBudgetsGiveBucketsOrAreRefused) {
  const ExternalOptions o = optionsForMemory(uint64_t(2048) << 20, TreeParams{}, 2);
  EXPECT_EQ(o.bucketTriangles, (uint64_t(2048) << 20) / 10 * 6 / kBuildBytesPerTriangle / 2);
  EXPECT_GT(o.bufferTriangles, 1000000u);
  EXPECT_GT(o.topTriangles, 1000000u);
  try {
    optionsForMemory(4096, TreeParams{}, 1);
    FAIL() << "a 4 KiB budget was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--mem-mb"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace lzb::sampletree
