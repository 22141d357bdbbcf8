// A rank's share streamed from a PLY (binary or ASCII), OFF or OBJ file (near the origin and
// recentred far from it), generated (builtin:landscape), or a TOML scene's streamed mesh files
// read per region, is the share cut from the loaded scene: the same regions, units, IDs, world
// triangles, colours, normals and node boxes, and the same outline.
#include "src/regions/streamed_share.hpp"

#include <gtest/gtest.h>

#include <string>

#include "src/scene/load.hpp"
#include "tests/support/files.hpp"
#include "tests/support/ply_files.hpp"
#include "tests/support/shares.hpp"
#include "tests/support/text_meshes.hpp"

namespace lzb::regions {
namespace {

// Calls check(regions, share, layout) for 1 and 5 regions, every rank of 1 to 3, both layouts.
template <class Check>
void forEveryShare(const std::string& spec, Check&& check) {
  for (const Parts layout : {Parts::kOne, Parts::kPerRegion})
    for (const uint32_t regions : {1u, 5u})
      for (const int ranks : {1, 2, 3})
        for (int rank = 0; rank < ranks; ++rank) {
          SCOPED_TRACE(spec + ": " + std::to_string(regions) + " regions, rank " +
                       std::to_string(rank) + " of " + std::to_string(ranks) +
                       (layout == Parts::kOne ? ", one part" : ", a part per region"));
          check(regions, WorkShare{rank, ranks}, layout);
        }
}

void expectStreamedEqualsCut(const std::string& spec) {
  const Scene whole = loadScene(spec, true);
  forEveryShare(spec, [&](uint32_t regions, const WorkShare& share, Parts layout) {
    const std::optional<ChunkedScene> chunked = openChunkedScene(spec, true);
    ASSERT_TRUE(chunked.has_value());
    SceneOutline outline;
    const HeldShare streamed = holdStreamedShare(*chunked, regions, share, layout, outline);
    test::expectSameOutline(outline, outlineOf(whole));
    test::expectSameShare(streamed, holdShare(whole, regions, share, layout, false), layout);
  });
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

// A TOML scene's mesh files read through its outline (loadSceneDeferred) give the parts cut from
// the loaded scene, for every layout, region and rank count; its procedural generators deferred
// too unless the method samples them (wholeProcedural).
void expectDeferredEqualsCut(const std::string& toml, size_t deferredFiles,
                             bool wholeProcedural = false) {
  const Scene whole = loadScene(toml, true);
  const TomlOutline outline = loadSceneDeferred(toml, true, !wholeProcedural);
  size_t deferred = 0;
  for (const Node& n : outline.scene.nodes) deferred += n.deferred.has_value();
  ASSERT_EQ(deferred, deferredFiles);
  test::expectSameOutline(outlineOf(outline.scene), outlineOf(whole));
  bool someSplit = false;
  forEveryShare(toml, [&](uint32_t regions, const WorkShare& share, Parts layout) {
    const HeldShare read =
        holdShare(outline.scene, regions, share, layout, wholeProcedural, outline.read);
    test::expectSameShare(read, holdShare(whole, regions, share, layout, wholeProcedural), layout);
    someSplit = someSplit || read.units > whole.nodes.size();
  });
  EXPECT_TRUE(someSplit) << "a file's mesh was cut into its triangles";
}

// Files placed once and cut into triangles, one far away and recentred with the scene's colour,
// one placed twice (a whole unit, read whole by the rank holding it), a landscape, a terrain and
// a displaced sphere generated per region (loaded whole for sqrt5), next to a generator loaded
// whole; a file of over 2^16 triangles (read in two chunks) as a scene's main mesh (through its
// recentred node), and cut beside another.
TEST(StreamedShare, ATomlScenesMeshFilesReadPerRegionGiveTheShareCutFromTheLoadedScene) {
  const test::ScratchDir dir;
  test::polygonMesh(test::PlyEncoding::kLittleEndian, 0.0, 12).write(dir.path() / "cut.ply");
  test::polygonMesh(test::PlyEncoding::kAscii, 1e7, 6).write(dir.path() / "far.ply");
  dir.write("twice.off", test::offGrid("COFF", 0.0));
  const std::string toml = dir.write("scene.toml", R"(root = "world"
[[meshes]]
name = "cut"
file = "cut.ply"
[[meshes]]
name = "far"
file = "far.ply"
color = [0.2, 0.4, 0.6]
[[meshes]]
name = "twice"
file = "twice.off"
[[generators]]
name = "flake"
spec = "sphereflake?depth=1"
[[generators]]
name = "land"
spec = "builtin:landscape?objects=12"
[[generators]]
name = "hills"
spec = "terrain?tess=12&extent=20"
[[generators]]
name = "ball"
spec = "displaced?shape=sphere&tess=10"
[[nodes]]
name = "world"
instances = [{ node = "cut" }, { node = "far", translate = [-1e7, 0, 5] },
             { node = "twice", translate = [0, 0, 30] }, { node = "twice", translate = [0, 9, 30] },
             { node = "flake", translate = [40, 0, 0] }, { node = "land", translate = [0, -80, 0] },
             { node = "hills", translate = [0, 60, 0] }, { node = "ball", translate = [9, 9, 9] }]
)")
                               .string();
  expectDeferredEqualsCut(toml, 6);
  expectDeferredEqualsCut(toml, 4, true);
  test::polygonMesh(test::PlyEncoding::kBigEndian, 1e7, 220).write(dir.path() / "large.ply");
  expectDeferredEqualsCut(dir.write("one.toml", R"(root = "world"
[[meshes]]
name = "far"
file = "large.ply"
[[nodes]]
name = "world"
instances = [{ node = "far", translate = [0, 0, 1] }]
)")
                              .string(),
                          1);
  expectDeferredEqualsCut(dir.write("two.toml", R"(root = "world"
[[meshes]]
name = "far"
file = "large.ply"
[[meshes]]
name = "cut"
file = "cut.ply"
[[nodes]]
name = "world"
instances = [{ node = "cut" }, { node = "far", translate = [-1e7, 0, 1] }]
)")
                              .string(),
                          2);
}

// The share's check runs once the regions are dealt, before any of its triangles is read: a file
// placed twice (a whole unit, cut by its bounds) is read only once the check has passed, and a
// check that refuses leaves it unread.
TEST(StreamedShare, ATomlShareIsCheckedBeforeItsTrianglesAreRead) {
  const test::ScratchDir dir;
  dir.write("twice.off", test::offGrid("COFF", 0.0));
  const std::string toml = dir.write("scene.toml", R"(root = "world"
[[meshes]]
name = "twice"
file = "twice.off"
[[nodes]]
name = "world"
instances = [{ node = "twice" }, { node = "twice", translate = [0, 9, 30] }]
)")
                               .string();
  const TomlOutline outline = loadSceneDeferred(toml, true, true);
  uint64_t reads = 0;
  const DeferredReader counted = [&](uint32_t node, const std::function<void(const Mesh&)>& out) {
    ++reads;
    outline.read(node, out);
  };
  const auto hold = [&](bool refuse) {
    return holdShare(outline.scene, 1, WorkShare{0, 1}, Parts::kOne, false, counted,
                     [&](const HeldShare& held) {
                       EXPECT_EQ(reads, 0u) << "read before the check";
                       EXPECT_EQ(held.triangles, outline.scene.expandedTriangles());
                       if (refuse) throw InputError("refused");
                     });
  };
  EXPECT_THROW(hold(true), InputError);
  EXPECT_EQ(reads, 0u);
  const HeldShare held = hold(false);
  EXPECT_GT(reads, 0u);
  EXPECT_EQ(held.parts.at(0).scene.uniqueTriangles(), outline.scene.uniqueTriangles());
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
}  // namespace lzb::regions
