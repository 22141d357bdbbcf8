#include "src/scene/mesh_file.hpp"

#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>

#include "src/core/error.hpp"
#include "src/scene/load.hpp"
#include "tests/support/files.hpp"

namespace lzb {
namespace {

using test::errorOf;
using test::ScratchDir;

const std::string kQuadObj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3\nf 1 3 4\n";
const std::string kPlyHeader =
    "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
    "property float z\nelement face 2\nproperty list uchar int vertex_indices\nend_header\n";
const std::string kPly = kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n";
const std::string kOff = "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n3 1 3 2\n";
const std::string kStl =
    "solid t\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n"
    "endloop\nendfacet\nendsolid t\n";

// The scene of one file, loaded like `lzb --scene file`.
Scene load(const std::filesystem::path& p) {
  return loadScene(p.string(), true);
}

void expectError(const std::filesystem::path& p, const std::string& part) {
  const std::string e = errorOf([&] { load(p); });
  EXPECT_NE(e.find(p.string()), std::string::npos) << "message must name the file: " << e;
  EXPECT_NE(e.find(part), std::string::npos) << "expected '" << part << "' in: " << e;
}

// ---- good files ----

TEST(MeshFile, ObjPlyOffStlLoad) {
  ScratchDir dir;
  for (const auto& [name, text, triangles] :
       std::vector<std::tuple<std::string, std::string, uint64_t>>{
           {"a.obj", kQuadObj, 2}, {"a.ply", kPly, 2}, {"a.off", kOff, 2}, {"a.stl", kStl, 1}}) {
    const Scene s = load(dir.write(name, text));
    EXPECT_EQ(s.expandedTriangles(), triangles) << name;
    EXPECT_EQ(s.stats.loaded, triangles) << name;
    EXPECT_EQ(s.stats.degenerate + s.stats.nonFinite, 0u) << name;
    EXPECT_EQ(s.rootNode().mesh.color(0), kDefaultMeshColor) << name;
    EXPECT_NEAR(s.bounds().hi.x, 1.0, 1e-9) << name;
    EXPECT_EQ(s.source, (dir.path() / name).string());
  }
}

TEST(MeshFile, EqualCornersAreStoredOnceWhateverTheFilesIndexing) {
  ScratchDir dir;
  // The quad indexed (OBJ) and as two triangles of their own corners (STL): 4 vertices each.
  const std::string stl =
      "solid q\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 1 1 0\n"
      "endloop\nendfacet\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\nvertex 1 1 0\n"
      "vertex 0 1 0\nendloop\nendfacet\nendsolid q\n";
  for (const auto& [name, text] :
       std::vector<std::pair<std::string, std::string>>{{"q.obj", kQuadObj}, {"q.stl", stl}}) {
    const Scene s = load(dir.write(name, text));
    const Mesh& m = s.rootNode().mesh;
    ASSERT_EQ(m.size(), 2u) << name;
    EXPECT_EQ(m.positions.size(), 4u) << name;
    EXPECT_EQ(m.vertex(1, 1), glm::vec3(1, 1, 0)) << name;
    EXPECT_EQ(m.colors.size(), 1u) << "one colour for the whole mesh: " << name;
  }
}

TEST(MeshFile, PolygonsAreTriangulated) {
  ScratchDir dir;
  // A quad and a concave pentagon (the notch at (2, 1)).
  const Scene s =
      load(dir.write("poly.obj",
                     "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 4 0 0\nv 4 4 0\nv 2 1 0\nv 0 4 0\n"
                     "f 1 2 3 4\nf 1 5 6 7 8\n"));
  EXPECT_EQ(s.expandedTriangles(), 2u + 3u);
  double area = 0.0;
  const Mesh& m = s.rootNode().mesh;
  for (size_t t = 0; t < m.size(); ++t) {
    EXPECT_FLOAT_EQ(m.normal(t).z, 1.0f);  // winding kept
    area += 0.5 * glm::length(glm::cross(glm::dvec3(m.vertex(t, 1) - m.vertex(t, 0)),
                                         glm::dvec3(m.vertex(t, 2) - m.vertex(t, 0))));
  }
  EXPECT_NEAR(area, 1.0 + 16.0 - 6.0, 1e-6);
}

TEST(MeshFile, MaterialVertexAndOverrideColours) {
  ScratchDir dir;
  dir.write("red.mtl", "newmtl red\nKd 1 0 0\n");
  const Scene obj = load(dir.write("red.obj", "mtllib red.mtl\nusemtl red\n" + kQuadObj));
  EXPECT_EQ(obj.rootNode().mesh.color(0), packRgba8(255, 0, 0));

  const Scene ply = load(
      dir.write("green.ply",
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
                "property float z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n"
                "element face 1\nproperty list uchar int vertex_indices\nend_header\n"
                "0 0 0 0 255 0\n1 0 0 0 255 0\n0 1 0 0 255 0\n3 0 1 2\n"));
  EXPECT_EQ(ply.rootNode().mesh.color(0), packRgba8(0, 255, 0));

  Scene scene;
  scene.root = addMeshFile(scene, dir.path() / "red.obj", packRgba8(1, 2, 3));
  EXPECT_EQ(scene.nodes[scene.root].mesh.color(1), packRgba8(1, 2, 3));
}

TEST(MeshFile, BinaryStl) {
  ScratchDir dir;
  std::string data(84, '\0');
  const uint32_t one = 1;
  std::memcpy(&data[80], &one, 4);
  const float tri[12] = {0, 0, 1, 0, 0, 0, 2, 0, 0, 0, 2, 0};
  data.append(reinterpret_cast<const char*>(tri), sizeof tri);
  data.append(2, '\0');
  EXPECT_EQ(load(dir.write("b.stl", data)).expandedTriangles(), 1u);
  expectError(dir.write("cut.stl", data.substr(0, data.size() - 7)), "truncated");
}

// ---- bad files ----

TEST(MeshFile, MissingDirectoryAndUnreadableFiles) {
  ScratchDir dir;
  expectError(dir.path() / "nothing.obj", "not found");
  std::filesystem::create_directories(dir.path() / "folder.obj");
  expectError(dir.path() / "folder.obj", "not a regular file");
  const auto locked = dir.write("locked.obj", kQuadObj);
  std::filesystem::permissions(locked, std::filesystem::perms::none);
  if (std::ifstream(locked).good()) GTEST_SKIP() << "running as root: permissions are not enforced";
  expectError(locked, "cannot be read");
}

TEST(MeshFile, EmptyFileAndZeroTriangles) {
  ScratchDir dir;
  expectError(dir.write("empty.obj", ""), "");
  expectError(dir.write("points.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "no valid triangles");
  expectError(dir.write("empty.ply", ""), "");
  expectError(dir.write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n"), "1 degenerate");
}

TEST(MeshFile, MalformedFiles) {
  ScratchDir dir;
  expectError(dir.write("badindex.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n"),
              "index out of range");
  expectError(dir.write("garbage.obj", "hello world\nthis is not a mesh\n"), "no valid triangles");
  expectError(dir.write("garbage.ply", "ply\nformat ascii 1.0\nelement vertex x\nend_header\n"),
              "malformed");
  expectError(dir.write("garbage.off", "OFF\nfour two zero\n"), "malformed");
  expectError(dir.write("garbage.glb", "glTF but not really"), "unknown GLB version");
  expectError(dir.write("noheader.ply", "ply\nformat ascii 1.0\nelement vertex 3\n"), "end_header");
}

TEST(MeshFile, TruncatedFiles) {
  ScratchDir dir;
  // Cut in the vertices, and cut after one of two faces (assimp would repeat the first face).
  expectError(dir.write("v.ply", kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n"), "truncated");
  expectError(dir.write("f.ply", kPlyHeader + "0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n"),
              "truncated");
  expectError(dir.write("v.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n"), "truncated");
  expectError(dir.write("f.off", "OFF\n4 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n3 0 1 2\n"), "truncated");
  expectError(dir.write("a.stl", kStl.substr(0, kStl.find("vertex 0 1 0"))), "");
  expectError(dir.write("b.stl", kStl.substr(0, kStl.find("endsolid"))), "truncated");
  // A binary PLY cut in its face list.
  std::string bin =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  bin.append(reinterpret_cast<const char*>(v), sizeof v);
  const int idx[3] = {0, 1, 2};
  bin.push_back(3);
  bin.append(reinterpret_cast<const char*>(idx), sizeof idx);
  EXPECT_EQ(load(dir.write("ok_bin.ply", bin)).expandedTriangles(), 1u);
  expectError(dir.write("cut_bin.ply", bin.substr(0, bin.size() - 4)), "truncated");
}

TEST(MeshFile, CountsNear2To64InHeadersDoNotWrapThePreChecks) {
  ScratchDir dir;
  // An OFF face of 2^64 - 1 vertices: "size >= k + 1" wrapped to "size >= 0" and passed.
  expectError(dir.write("face.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n18446744073709551615 0 1 2\n"),
              "malformed OFF face 0");
  // A binary PLY list counted by an 8-byte double: 2^62 items times 4 bytes wrapped to 0 and
  // passed, while assimp reads the same bytes as the double 2.0.
  std::string ply =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list double int vertex_indices\nend_header\n";
  const float v[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  ply.append(reinterpret_cast<const char*>(v), sizeof v);
  ply.append(7, '\0');
  ply.push_back('\x40');
  expectError(dir.write("list.ply", ply), "count type must be an integer");
  // The largest integer count, 2^32 - 1 items of 8 bytes, in a short file.
  std::string big =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uint double vertex_indices\nend_header\n";
  big.append(reinterpret_cast<const char*>(v), sizeof v);
  big.append(4, '\xff');
  big.append(24, '\0');
  expectError(dir.write("big.ply", big), "truncated");
}

TEST(MeshFile, OffIndicesPastTheVerticesAreRefused) {
  ScratchDir dir;
  // assimp would clamp index 7 to the last vertex and load a triangle the file does not hold.
  expectError(dir.write("far.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n"),
              "vertex index '7' is not one of the 3 vertices");
  expectError(dir.write("neg.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n"),
              "vertex index '-1'");
}

// Inputs the fuzzers found (tests/fuzz/regressions): each crashed, hung or exhausted memory in
// assimp before the pre-checks refused it.
TEST(MeshFile, FuzzFindingsAreRefusedBeforeAssimp) {
  ScratchDir dir;
  expectError(dir.write("empty_face.off", "OFF 3 1 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n"),
              "malformed OFF face 0: it has no vertices");
  expectError(dir.write("keyword.off", "OFF4 4 0\n0 0 0\n3 1 0\n0 0 0\n3 1 0\n"),
              "malformed OFF header keyword 'OFF4'");
  expectError(dir.write("comment.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n# c\n3 0 1 2\n"),
              "a comment line among the OFF vertices or faces: '# c'");
  expectError(dir.write("ten.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n10 0 1 2 0 1 2 0 1 2 0\n"),
              "OFF face 0 has 10 vertices; the reader (assimp) takes at most 9");
  EXPECT_EQ(load(dir.write("c.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 255 0 0 255\n"
                                     "0 1 0 255 0 0 255\n3 0 1 2\n"))
                .expandedTriangles(),
            1u);
  // "3ascii" read as 3 by a stream, an element without properties, a misspelt keyword: assimp
  // looped forever on this header.
  const std::string props = "property float x\nproperty float y\nproperty float z\n";
  expectError(dir.write("count.ply", "ply\nformat ascii 1.0\nelement vertex 3ascii\n" + props +
                                         "end_header\n0 0 0\n1 0 0\n0 1 0\n"),
              "malformed PLY header line 'element vertex 3ascii'");
  expectError(dir.write("bare.ply", "ply\nformat ascii 1.0\nelement vertex 3\nelement face 0\n" +
                                        props + "end_header\n"),
              "PLY element 'vertex' has no properties");
  // Free text in a header passes, as assimp reads it (Blender 2.47 wrote such lines).
  EXPECT_EQ(load(dir.write("text.ply", "ply\nformat ascii 1.0\nCreated by hand\nelement vertex 3\n" +
                                           props + "element face 1\n"
                                           "property list uchar int vertex_indices\nend_header\n"
                                           "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"))
                .expandedTriangles(),
            1u);
  expectError(dir.write("inline.ply", "ply\nformat ascii 1.0\nelement vertex 0\nfoo/end_header\n"),
              "end_header is not on a line of its own");
  expectError(dir.write("nul.ply", std::string("ply\nformat ascii 1.0\nco\0mment\nelement vertex 0\n"
                                                "property float x\nend_header\n",
                                                75)),
              "PLY header holds a NUL byte");
  expectError(dir.write("novertex.ply", "ply\nformat binary_big_endian 1.0\nelemeexces\nend_header\n"),
              "PLY header declares no 'vertex' element");
  expectError(dir.write("run_on.ply", "ply\nformat ascii 1.0\nelement vertex 0\nend_headerat x\n"),
              "end_header is not on a line of its own");
  // A GLB whose JSON chunk claims 0x600002a4 bytes in a 200-byte file.
  std::string glb("glTF\x02\0\0\0\xc8\0\0\0\xa4\x02\0\x60JSON", 20);
  glb.resize(200, ' ');
  expectError(dir.write("chunk.glb", glb), "a GLB chunk of 1610613412 bytes runs past");
  std::string empty("glTF\x02\0\0\0\0\0\0\0", 12);
  empty.resize(163, '\0');
  expectError(dir.write("empty.glb", empty), "its first chunk is not the JSON chunk");
  std::string longer("glTF\x02\0\0\0\x00\x10\0\0", 12);
  expectError(dir.write("long.glb", longer), "the GLB header promises 4096 bytes, the file has 12");
}

TEST(MeshFile, NanAndDegenerateTrianglesAreDroppedAndCounted) {
  ScratchDir dir;
  const Scene s = load(dir.write("bad.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 1 0\nv 2 0 0\nv 0 inf 0\n"
                                 "f 1 2 3\nf 2 4 3\nf 1 2 5\nf 1 2 6\nf 1 1 3\n"));
  EXPECT_EQ(s.expandedTriangles(), 1u);
  EXPECT_EQ(s.stats.loaded, 1u);
  EXPECT_EQ(s.stats.nonFinite, 2u);
  EXPECT_EQ(s.stats.degenerate, 2u);  // collinear, and a repeated vertex
}

TEST(MeshFile, FarFromOriginIsRecentred) {
  ScratchDir dir;
  // A unit triangle at 1e7: float spacing there is 1, so positions must not be stored as is.
  const Scene s =
      load(dir.write("far.obj", "v 10000000 0 0\nv 10000001 0 0\nv 10000000 1 5\nf 1 2 3\n"));
  ASSERT_EQ(s.expandedTriangles(), 1u);
  const auto ref = s.resolve(0);
  ASSERT_TRUE(ref.has_value());
  const Mesh& m = s.nodes[ref->node].mesh;
  for (int k = 0; k < 3; ++k) EXPECT_LT(glm::length(m.vertex(0, k)), 10.0f);
  const glm::dvec3 w1 = glm::dvec3(ref->transform * glm::dvec4(glm::dvec3(m.vertex(0, 1)), 1.0));
  EXPECT_EQ(w1, glm::dvec3(10000001.0, 0.0, 0.0));
  EXPECT_NEAR(ref->transform[3].x, 10000000.5, 1e-9);
  EXPECT_NEAR(s.bounds().lo.x, 1e7, 1e-9);
  EXPECT_NEAR(s.bounds().hi.z, 5.0, 1e-9);
  // Near the origin nothing moves.
  const Scene near = load(dir.write("near.obj", "v 1 0 0\nv 2 0 0\nv 1 1 0\nf 1 2 3\n"));
  EXPECT_EQ(near.nodes.size(), 1u);
  EXPECT_TRUE(near.rootNode().instances.empty());
}

TEST(MeshFile, GltfNodesSharingAMeshBecomeInstances) {
  ScratchDir dir;
  const Scene s = load(dir.write("two.gltf", R"({
  "asset": {"version": "2.0"},
  "scene": 0,
  "scenes": [{"nodes": [0, 1]}],
  "nodes": [{"mesh": 0, "translation": [5, 0, 0]}, {"mesh": 0, "scale": [2, 2, 2]}],
  "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
  "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                 "min": [0, 0, 0], "max": [1, 1, 0]}],
  "bufferViews": [{"buffer": 0, "byteLength": 36}],
  "buffers": [{"byteLength": 36,
               "uri": "data:application/octet-stream;base64,AAAAAAAAAAAAAAAAAACAPwAAAAAAAAAAAAAAAAAAgD8AAAAA"}]
})"));
  EXPECT_EQ(s.uniqueTriangles(), 1u);
  EXPECT_EQ(s.expandedTriangles(), 2u);
  ASSERT_EQ(s.rootNode().instances.size(), 2u);
  EXPECT_EQ(s.rootNode().instances[0].node, s.rootNode().instances[1].node);
  EXPECT_NEAR(s.bounds().lo.x, 0.0, 1e-6);
  EXPECT_NEAR(s.bounds().hi.x, 6.0, 1e-6);
  EXPECT_NEAR(s.bounds().hi.y, 2.0, 1e-6);
}

TEST(MeshFile, ObjGroupsUsedOnceAreBakedIntoOneNode) {
  ScratchDir dir;
  const Scene s = load(dir.write("groups.obj",
                                 "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n"
                                 "g a\nf 1 2 3\ng b\nf 1 2 4\n"));
  EXPECT_EQ(s.nodes.size(), 1u);
  EXPECT_EQ(s.expandedTriangles(), 2u);
}

// ---- real files from the Debian package assimp-testmodels ----

TEST(MeshFile, AssimpTestModels) {
  const std::filesystem::path root = "/usr/share/assimp/models";
  if (!std::filesystem::exists(root)) GTEST_SKIP() << "assimp-testmodels not installed";
  const Scene cube = load(root / "PLY/cube.ply");
  EXPECT_EQ(cube.expandedTriangles(), 12u);  // 6 quads
  EXPECT_NEAR(cube.bounds().extent().x, cube.bounds().extent().y, 1e-6);
  const Scene box = load(root / "OBJ/box.obj");
  EXPECT_EQ(box.expandedTriangles(), 12u);
  const Scene spider = load(root / "OBJ/spider.obj");
  EXPECT_GT(spider.expandedTriangles(), 1000u);
  EXPECT_GT(load(root / "STL/Spider_binary.stl").expandedTriangles(), 1000u);
  const std::filesystem::path glb = root / "glTF2/BoxTextured-glTF-Binary/BoxTextured.glb";
  if (std::filesystem::exists(glb)) {
    EXPECT_EQ(load(glb).expandedTriangles(), 12u);
  }
  expectError(root / "OFF/invalid.off", "");
}

}  // namespace
}  // namespace lzb
