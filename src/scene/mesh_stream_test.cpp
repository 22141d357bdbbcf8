// A mesh file streamed (mesh_stream.hpp) gives the triangles the loaded scene holds, bit for bit
// and in ID order, with its placement; what the loader might read otherwise is left to it, and
// what it refuses is refused. (PLY: src/sampletree/ply_input_test.cpp.)
#include "src/scene/mesh_stream.hpp"

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/scene/load.hpp"
#include "tests/support/assimp_scene.hpp"
#include "tests/support/files.hpp"
#include "tests/support/meshes.hpp"
#include "tests/support/text_meshes.hpp"

namespace lzb {
namespace {

using test::objGrid;
using test::offGrid;

void expectStreamedEqualsLoaded(const std::filesystem::path& file) {
  SCOPED_TRACE(file.string());
  std::string why;
  const std::unique_ptr<MeshStream> s = MeshStream::open(file, why);
  ASSERT_TRUE(s) << why;
  const Scene scene = test::loadedByAssimp(file);
  const Scene loaded = loadScene(file.string(), true);  // through the stream
  ASSERT_EQ(s->triangles(), scene.expandedTriangles());
  ASSERT_EQ(loaded.expandedTriangles(), scene.expandedTriangles());
  EXPECT_EQ(s->stats().degenerate, scene.stats.degenerate);
  EXPECT_EQ(s->stats().nonFinite, scene.stats.nonFinite);
  uint64_t id = 0;
  s->forEachChunk(
      [&](const Mesh& m) {
        for (size_t t = 0; t < m.size(); ++t, ++id) {
          const auto r = scene.resolve(id);
          ASSERT_TRUE(r);
          const Mesh& assimp = scene.nodes[r->node].mesh;
          const auto l = loaded.resolve(id);
          ASSERT_TRUE(l);
          const Mesh& viaStream = loaded.nodes[l->node].mesh;
          for (int k = 0; k < 3; ++k) {
            ASSERT_EQ(m.vertex(t, k), assimp.vertex(r->triangle, k)) << "triangle " << id;
            ASSERT_EQ(viaStream.vertex(l->triangle, k), assimp.vertex(r->triangle, k));
          }
          ASSERT_EQ(m.color(t), assimp.color(r->triangle)) << "triangle " << id;
          ASSERT_EQ(viaStream.color(l->triangle), assimp.color(r->triangle)) << "triangle " << id;
          ASSERT_EQ(s->placement(), r->transform);
          ASSERT_EQ(l->transform, r->transform);
        }
      },
      50);
  EXPECT_EQ(id, scene.expandedTriangles());
}

std::string leftToLoader(const std::filesystem::path& file) {
  std::string why;
  EXPECT_EQ(MeshStream::open(file, why), nullptr) << file;
  return why;
}

std::string refusal(const std::filesystem::path& file) {
  try {
    std::string why;
    MeshStream::open(file, why);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(MeshStream, OffStreamsAsLoaded) {
  const test::ScratchDir dir;
  for (const std::string keyword : {"OFF", "COFF", "NOFF", "CNOFF"})
    expectStreamedEqualsLoaded(dir.write(keyword + ".off", offGrid(keyword, 0.0)));
  expectStreamedEqualsLoaded(dir.write("crlf.off", offGrid("COFF", 0.0, "\r\n")));
  expectStreamedEqualsLoaded(dir.write("far.off", offGrid("OFF", 1e7)));
  // Counts on the keyword's line; 123.456e2 reads 12345.6006 there, not strtof's 12345.5996,
  // and 0,5 reads 0.5.
  expectStreamedEqualsLoaded(
      dir.write("spelled.off",
                "OFF 4 2 0\n123.456e2 0 0\n1 0 0,5\n1. 1 -0\n+0 1 1e-2\n3 0 1 2\n"
                "3 0 2 3\n"));
}

// Scans as CGAL ships them (a blank line after the counts, 10 digits a value, 10^4 to 7.5 10^4
// faces).
TEST(MeshStream, ScannedOffMeshesStreamAsLoaded) {
  for (const char* name : {"bunny00.off", "ChineseDragon-10kv.off", "armadillo.off"}) {
    const std::string file = test::scannedMesh(name);
    if (file.empty()) GTEST_SKIP() << "no scanned meshes (scripts/fetch-test-meshes.sh)";
    expectStreamedEqualsLoaded(file);
  }
}

TEST(MeshStream, OffTheLoaderMightReadOtherwiseIsLeftToIt) {
  const test::ScratchDir dir;
  const std::string body = "0 0 0\n1 0 0\n1 1 0\n3 0 1 2\n";
  const std::pair<std::string, std::string> cases[] = {
      {"COFF\n3 1 0\n0 0 0 1 0 0\n1 0 0 1 0 0\n1 1 0 1 0 0\n3 0 1 2\n", "fewer values"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n  \n1 1 0\n3 0 1 2\n", "only spaces"},
      {"OFF\n3 1 0\n0 0 0\n# a comment\n1 0 0\n1 1 0\n3 0 1 2\n", "not one plain number"},
      {"OFF\n3 1\n0\n" + body, "three counts"},
      {"4OFF\n3 1 0\n" + body, "header other"},
      {"STOFF\n3 1 0\n" + body, "header other"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n3 0 1 3\n", "past the vertices"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\n1 1 0\n10 0 1 2 0 1 2 0 1 2 0\n", "more than 9"},
      {"OFF\n3 1 0\n0 0 0\n1 0 0\r1 1 0\n3 0 1 2\n", "carriage return"},
  };
  for (const auto& [text, reason] : cases) {
    const std::string why = leftToLoader(dir.write("otherwise.off", text));
    EXPECT_NE(why.find(reason), std::string::npos) << text << why;
  }
  const std::filesystem::path cut = dir.write("cut.off", "OFF\n3 2 0\n" + body);
  EXPECT_NE(refusal(cut).find(cut.string() + ": truncated: the header promises 2 faces"),
            std::string::npos)
      << refusal(cut);
  const std::filesystem::path none =
      dir.write("none.off", "OFF\n3 1 0\n0 0 0\n1 1 1\n2 2 2\n3 0 1 2\n");
  EXPECT_NE(refusal(none).find("no valid triangles"), std::string::npos) << refusal(none);
}

TEST(MeshStream, ObjStreamsAsLoaded) {
  const test::ScratchDir dir;
  expectStreamedEqualsLoaded(dir.write("plain.obj", objGrid(false, 0.0)));
  expectStreamedEqualsLoaded(dir.write("coloured.obj", objGrid(true, 0.0)));
  expectStreamedEqualsLoaded(dir.write("crlf.obj", objGrid(true, 0.0, "\r\n")));
  expectStreamedEqualsLoaded(dir.write("far.obj", objGrid(false, 1e7)));
  // A face naming vertices defined after it; no line end at the end; 123.456e2 as assimp reads it.
  expectStreamedEqualsLoaded(
      dir.write("forward.obj", "f 1 2 3\nv 123.456e2 0 0\nv 1 0 0,5\nv -.5 1 1e-2\nf 1 2 3"));
}

TEST(MeshStream, ObjTheLoaderMightReadOtherwiseIsLeftToIt) {
  const test::ScratchDir dir;
  const std::string v = "v 0 0 0\nv 1 0 0\nv 1 1 0\n";
  const std::pair<std::string, std::string> cases[] = {
      {"mtllib a.mtl\n" + v + "f 1 2 3\n", "'mtllib'"},
      {v + "usemtl red\nf 1 2 3\n", "'usemtl'"},
      {v + "l 1 2\nf 1 2 3\n", "'l'"},
      {v + " f 1 2 3\n", "indented"},
      {v + "f +1 2 3\n", "'+1'"},
      {v + "f 01 2 3\n", "'01'"},
      {v + "f 1/1/1/1 2 3\n", "three parts"},
      {v + "f 1 2 4\n", "past the vertices"},
      {v + "f 1 2 -4\n", "past the vertices"},
      {v + "f 1 2 0\n", "'0'"},
      {"v 0 0 0 1\n" + v + "f 1 2 3\n", "3 or 6"},
      {"v 0 0 0 1 0 0\n" + v + "f 1 2 3\n", "with and without colours"},
      {"v .5 0 0\n" + v + "f 1 2 3\n", "'.5'"},
      {v + "f 1 2 3\ng other\nf 1 2 3\n", "after the first face"},
      {v + "f 1 2 \\\n3\n", "backslash"},
      {v + "# no faces\n", "no faces"},
  };
  for (const auto& [text, reason] : cases) {
    const std::string why = leftToLoader(dir.write("otherwise.obj", text));
    EXPECT_NE(why.find(reason), std::string::npos) << text << why;
  }
  const std::filesystem::path none = dir.write("none.obj", v + "f 1 1 2\n");
  EXPECT_NE(refusal(none).find("no valid triangles"), std::string::npos) << refusal(none);
}

}  // namespace
}  // namespace lzb
