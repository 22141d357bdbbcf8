// A rank's share streamed from a PLY (binary or ASCII), OFF or OBJ file (near the origin and
// recentred far from it) or generated (builtin:landscape) is the share cut from the loaded scene:
// the same regions, units, IDs, world triangles, colours, normals and node boxes, and the same
// outline.
#include "src/cli/streamed_share.hpp"

#include <gtest/gtest.h>

#include <string>

#include "src/scene/load.hpp"
#include "tests/support/files.hpp"
#include "tests/support/ply_files.hpp"
#include "tests/support/text_meshes.hpp"

namespace lzb {
namespace {

void expectSameOutline(const SceneOutline& a, const SceneOutline& b) {
  EXPECT_EQ(a.source, b.source);
  EXPECT_EQ(a.bounds.lo, b.bounds.lo);
  EXPECT_EQ(a.bounds.hi, b.bounds.hi);
  EXPECT_EQ(a.uniqueTriangles, b.uniqueTriangles);
  EXPECT_EQ(a.expandedTriangles, b.expandedTriangles);
  EXPECT_EQ(a.nodes, b.nodes);
  EXPECT_EQ(a.instanceDepth, b.instanceDepth);
  EXPECT_EQ(a.stats.loaded, b.stats.loaded);
  EXPECT_EQ(a.stats.degenerate, b.stats.degenerate);
  EXPECT_EQ(a.camera.has_value(), b.camera.has_value());
}

// Everything a renderer of the part sees, triangle by triangle, in world space.
void expectSamePart(const ScenePart& streamed, const ScenePart& cut) {
  const Scene &s = streamed.scene, &c = cut.scene;
  ASSERT_EQ(s.expandedTriangles(), c.expandedTriangles());
  EXPECT_EQ(streamed.units, cut.units);
  if (s.expandedTriangles() == 0) return;
  EXPECT_EQ(s.bounds().lo, c.bounds().lo);
  EXPECT_EQ(s.bounds().hi, c.bounds().hi);
  for (uint64_t id = 0; id < s.expandedTriangles(); ++id) {
    ASSERT_EQ(streamed.ids.global(id), cut.ids.global(id)) << id;
    const auto a = s.resolve(id), b = c.resolve(id);
    ASSERT_TRUE(a && b);
    EXPECT_EQ(a->transform, b->transform) << id;
    EXPECT_EQ(s.nodeBounds[a->node].lo, c.nodeBounds[b->node].lo) << id;
    EXPECT_EQ(s.nodeBounds[a->node].hi, c.nodeBounds[b->node].hi) << id;
    const Mesh &ma = s.nodes[a->node].mesh, &mb = c.nodes[b->node].mesh;
    for (int k = 0; k < 3; ++k) EXPECT_EQ(ma.vertex(a->triangle, k), mb.vertex(b->triangle, k));
    EXPECT_EQ(ma.normal(a->triangle), mb.normal(b->triangle));
    EXPECT_EQ(ma.color(a->triangle), mb.color(b->triangle));
  }
}

void expectStreamedEqualsCut(const std::string& spec) {
  const Scene whole = loadScene(spec, true);
  for (const Parts layout : {Parts::kOne, Parts::kPerRegion})
    for (const uint32_t regions : {1u, 5u})
      for (const int ranks : {1, 2, 3})
        for (int rank = 0; rank < ranks; ++rank) {
          SCOPED_TRACE(spec + ": " + std::to_string(regions) + " regions, rank " +
                       std::to_string(rank) + " of " + std::to_string(ranks) +
                       (layout == Parts::kOne ? ", one part" : ", a part per region"));
          const std::optional<ChunkedScene> chunked = openChunkedScene(spec, true);
          ASSERT_TRUE(chunked.has_value());
          SceneOutline outline;
          const HeldShare streamed =
              holdStreamedShare(*chunked, regions, {rank, ranks}, layout, outline);
          const HeldShare cut = holdShare(whole, regions, {rank, ranks}, layout, false);
          expectSameOutline(outline, outlineOf(whole));
          EXPECT_EQ(streamed.regions, cut.regions);
          EXPECT_EQ(streamed.units, cut.units);
          EXPECT_EQ(streamed.mine, cut.mine);
          ASSERT_EQ(streamed.parts.size(), cut.parts.size());
          EXPECT_EQ(cut.parts.size(), layout == Parts::kOne ? 1u : cut.mine.size());
          for (size_t p = 0; p < cut.parts.size(); ++p)
            expectSamePart(streamed.parts[p], cut.parts[p]);
        }
}

TEST(StreamedShare, AMeshFileStreamedGivesTheShareCutFromTheLoadedScene) {
  const test::ScratchDir dir;
  for (const auto encoding : {test::PlyEncoding::kLittleEndian, test::PlyEncoding::kAscii})
    expectStreamedEqualsCut(test::polygonMesh(encoding, 0.0, 12).write(dir.path() / "near.ply"));
  expectStreamedEqualsCut(dir.write("near.off", test::offGrid("COFF", 0.0)).string());
  expectStreamedEqualsCut(dir.write("far.obj", test::objGrid(true, 1e7)).string());
}

TEST(StreamedShare, AFarPlyFileIsSplitThroughItsRecentredNode) {
  const test::ScratchDir dir;
  const std::string far =
      test::polygonMesh(test::PlyEncoding::kBigEndian, 1e7, 12).write(dir.path() / "far.ply");
  const Scene whole = loadScene(far, true);
  ASSERT_NE(whole.rootNode().instances.size(), 0u) << "the loader recentres it";
  const SceneUnits units = sceneUnits(whole, 4);
  EXPECT_EQ(units.meshPath, std::vector<uint32_t>{0});
  EXPECT_EQ(units.meshTriangles, whole.expandedTriangles()) << "each triangle a unit";
  expectStreamedEqualsCut(far);
}

TEST(StreamedShare, AGeneratedLandscapeGivesTheShareCutFromTheLoadedScene) {
  expectStreamedEqualsCut("builtin:landscape?objects=20");
}

// A procedural object streamed in grid rows: the share cut from the loaded tessellation (the
// sphere's degenerate pole halves dropped alike), its outline and camera.
TEST(StreamedShare, AProceduralObjectGeneratedInRowsGivesTheShareCutFromTheLoadedScene) {
  expectStreamedEqualsCut("builtin:terrain?tess=24");
  expectStreamedEqualsCut("builtin:displaced?shape=sphere&tess=20");
  expectStreamedEqualsCut("builtin:displaced?tess=130");  // chunks of 126 and 4 rows
}

TEST(StreamedShare, OtherScenesAreNotStreamed) {
  EXPECT_FALSE(openChunkedScene("builtin:city?blocks=1", true).has_value());
  const test::ScratchDir dir;
  EXPECT_FALSE(
      openChunkedScene(
          dir.write("a.obj", "mtllib a.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n").string(), true)
          .has_value());
  EXPECT_FALSE(openChunkedScene(dir.write("a.stl", "solid a\nendsolid a\n").string(), true));
}

}  // namespace
}  // namespace lzb
