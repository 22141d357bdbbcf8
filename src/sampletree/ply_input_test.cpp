// A PLY file streamed (src/scene/ply_stream.hpp through MeshChunkStream) gives the triangles the
// scene loaded by assimp streams (SceneStream), bit for bit: polygons split, vertex colours
// averaged, degenerate and non-finite faces dropped, far geometry recentred, in either byte order
// and in ASCII; malformed files are refused naming the file, and files the loader reads otherwise
// are left to it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "src/core/error.hpp"
#include "src/sampletree/triangle_stream.hpp"
#include "src/scene/ply_stream.hpp"
#include "tests/support/assimp_scene.hpp"
#include "tests/support/ply_files.hpp"

namespace lzb::sampletree {
namespace {

namespace fs = std::filesystem;
using test::PlyEncoding;
using test::PlyFile;
using test::polygonMesh;

fs::path scratch(const std::string& name) {
  const fs::path dir = fs::temp_directory_path() / "lzb_ply_input_test";
  fs::create_directories(dir);
  return dir / name;
}

std::vector<StreamTriangle> gather(const TriangleStream& s) {
  std::vector<StreamTriangle> all;
  s.forEach([&](std::span<const StreamTriangle> b) { all.insert(all.end(), b.begin(), b.end()); });
  return all;
}

// The streamed file against the loaded one, triangle by triangle (in chunks of 50 triangles).
void expectStreamedEqualsLoaded(const fs::path& file) {
  std::string why;
  const auto ply = PlyMeshStream::open(file, why);
  ASSERT_TRUE(ply) << why;
  const Scene scene = test::loadedByAssimp(file);
  SceneOutline base;
  base.source = file.string();
  const MeshChunkStream streamed(base, ply->triangles(),
                                 [&](const auto& out) {
                                   ply->forEachChunk(out, 50);
                                   return ply->stats();
                                 },
                                 MeshChunkStream::Kind::kFile, ply->placement());
  const std::vector<StreamTriangle> a = gather(streamed), b = gather(SceneStream(scene));
  // What the store keeps for a render without the scene: the loaded scene's outline exactly.
  EXPECT_EQ(outlineText(streamed.outline()), outlineText(outlineOf(scene)));
  EXPECT_EQ(ply->triangles(), scene.expandedTriangles());
  EXPECT_EQ(ply->stats().degenerate, scene.stats.degenerate);
  EXPECT_EQ(ply->stats().nonFinite, scene.stats.nonFinite);
  ASSERT_EQ(a.size(), b.size());
  for (size_t t = 0; t < a.size(); ++t)
    ASSERT_EQ(std::memcmp(&a[t], &b[t], sizeof(StreamTriangle)), 0) << "triangle " << t;
}

TEST(PlyInput, PolygonsAndColoursStreamAsLoaded) {
  const fs::path file = polygonMesh(PlyEncoding::kLittleEndian, 0.0).write(scratch("polygons.ply"));
  expectStreamedEqualsLoaded(file);
  std::string why;
  const auto ply = PlyMeshStream::open(file, why);
  EXPECT_GT(ply->stats().degenerate, 0u);  // lines and repeated corners
  EXPECT_GT(ply->stats().nonFinite, 0u);   // the NaN vertex
  EXPECT_GT(ply->triangles(), 700u);       // 529 faces, polygons split
  EXPECT_EQ(ply->placement(), glm::dmat4(1.0));
  std::vector<Rgba8> colours;
  ply->forEachChunk(
      [&](const Mesh& m) { colours.insert(colours.end(), m.colors.begin(), m.colors.end()); });
  std::sort(colours.begin(), colours.end());
  EXPECT_GT(std::unique(colours.begin(), colours.end()) - colours.begin(),
            500);  // vertex colours averaged
}

TEST(PlyInput, BigEndianStreamsAsLoaded) {
  expectStreamedEqualsLoaded(polygonMesh(PlyEncoding::kBigEndian, 0.0).write(scratch("big.ply")));
}

TEST(PlyInput, FarGeometryIsRecentredAsLoaded) {
  const fs::path file = polygonMesh(PlyEncoding::kLittleEndian, 1e7).write(scratch("far.ply"));
  expectStreamedEqualsLoaded(file);
  std::string why;
  EXPECT_NE(PlyMeshStream::open(file, why)->placement(), glm::dmat4(1.0));
}

// Float positions, float colours, uint counts and indices, no colour on some channels.
TEST(PlyInput, OtherTypesStreamAsLoaded) {
  PlyFile f;
  f.header =
      "element vertex 5\nproperty float x\nproperty float y\nproperty float z\n"
      "property float r\nproperty ushort blue\nelement face 3\n"
      "property list uint uint vertex_index\n";
  const float p[5][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {0.5f, 0.5f, 1}};
  for (int v = 0; v < 5; ++v) {
    for (float c : p[v]) f.put(c);
    f.put(0.1f * float(v)), f.put(uint16_t(9000 * v));
  }
  for (const std::vector<uint32_t>& face :
       std::vector<std::vector<uint32_t>>{{0, 1, 2, 3}, {0, 1, 4}, {2, 3, 4}}) {
    f.put(uint32_t(face.size()));
    for (uint32_t v : face) f.put(v);
  }
  expectStreamedEqualsLoaded(f.write(scratch("types.ply")));
}

std::string refusal(const fs::path& file) {
  try {
    std::string why;
    PlyMeshStream::open(file, why);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(PlyInput, MalformedFilesAreRefusedNamingTheFile) {
  const PlyFile good = polygonMesh(PlyEncoding::kLittleEndian, 0.0, 6);
  for (const size_t cut : {size_t(0), size_t(100), good.data.size() / 2, good.data.size() - 20,
                           good.data.size() - 1}) {
    PlyFile f = good;
    f.data.resize(cut);
    const fs::path file = f.write(scratch("cut.ply"));
    const std::string e = refusal(file);
    EXPECT_NE(e.find(file.string()), std::string::npos) << cut << ": " << e;
    EXPECT_NE(e.find("truncated"), std::string::npos) << cut << ": " << e;
  }
  PlyFile range;
  range.header =
      "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\n";
  for (int k = 0; k < 9; ++k) range.put(float(k % 4 == 0));
  range.put(uint8_t(3)), range.put(int32_t(0)), range.put(int32_t(1)), range.put(int32_t(3));
  const fs::path out = range.write(scratch("range.ply"));
  EXPECT_NE(refusal(out).find(out.string() + ": malformed: face 0 uses vertex 3 of 3"),
            std::string::npos)
      << refusal(out);
  PlyFile empty = range;
  empty.data.resize(empty.data.size() - 13);
  empty.put(uint8_t(0));
  EXPECT_NE(refusal(empty.write(scratch("empty.ply"))).find("face 0 has no vertices"),
            std::string::npos);
  PlyFile header = range;
  header.header += "property list float int bad\n";
  EXPECT_NE(refusal(header.write(scratch("header.ply"))).find("integer type"), std::string::npos);
  EXPECT_NE(refusal(scratch("missing.ply")).find("file not found"), std::string::npos);
}

// Why `file` is left to the loader ("" and a failure if it is streamed).
std::string why(const fs::path& file) {
  std::string reason;
  EXPECT_EQ(PlyMeshStream::open(file, reason), nullptr) << file;
  return reason;
}

// What the loader (assimp 5.2) reads otherwise, or this reader does not stream, is left to it.
TEST(PlyInput, FilesTheLoaderReadsOtherwiseAreLeftToIt) {
  PlyFile comment = polygonMesh(PlyEncoding::kLittleEndian, 0.0, 4);
  comment.header.insert(comment.header.find("property double y"), "comment between properties\n");
  EXPECT_NE(why(comment.write(scratch("comment.ply"))).find("property line after"),
            std::string::npos);
  PlyFile strips = polygonMesh(PlyEncoding::kLittleEndian, 0.0, 4);
  strips.header += "element tristrips 0\nproperty list int int vertex_indices\n";
  EXPECT_NE(why(strips.write(scratch("strips.ply"))).find("strips"), std::string::npos);
}

TEST(PlyInput, AsciiStreamsAsLoaded) {
  expectStreamedEqualsLoaded(polygonMesh(PlyEncoding::kAscii, 0.0).write(scratch("text.ply")));
  expectStreamedEqualsLoaded(polygonMesh(PlyEncoding::kAscii, 1e7).write(scratch("far_text.ply")));
}

// A small ASCII PLY written with its lines as given: after "end_header\n", `body`.
fs::path asciiPly(const std::string& name, const std::string& body) {
  const fs::path file = scratch(name);
  std::ofstream(file, std::ios::binary)
      << "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\n"
         "property double z\nproperty uchar red\nelement face 2\n"
         "property list uchar int vertex_indices\nend_header\n"
      << body;
  return file;
}

// Line ends, spacing and number spellings that the loader reads as this reader does (123.456e2
// reads as 12345.6006 there, not as strtof's 12345.5996).
TEST(PlyInput, AsciiSpellingsStreamAsLoaded) {
  expectStreamedEqualsLoaded(
      asciiPly("crlf.ply", "0 0 0 9\r\n1 0 0 200\r\n1 1 0 3\r\n0 1 0 0\r\n3 0 1 2\r\n3 0 2 3\r\n"));
  expectStreamedEqualsLoaded(asciiPly("spacing.ply",
                                      "  0\t0  0 9 \n123.456e2 -0 .0 200\n+1 1. 1e-2 3\t\n"
                                      "0 1 -1E+1 0\n3 0 1 2\n4\t0 1 2 3\n\n\r\n"));
}

// Where the loader could read other values (or lines), the file is left to it.
TEST(PlyInput, AsciiTheLoaderMightReadOtherwiseIsLeftToIt) {
  const std::string good = "0 0 0 9\n1 0 0 200\n1 1 0 3\n0 1 0 0\n3 0 1 2\n3 0 2 3\n";
  const std::pair<std::string, std::string> cases[] = {
      {"0 0 0 9\n\n1 0 0 200\n1 1 0 3\n0 1 0 0\n3 0 1 2\n3 0 2 3\n", "blank line"},
      {"0 0 0 9 1\n1 0 0 200\n1 1 0 3\n0 1 0 0\n3 0 1 2\n3 0 2 3\n", "more values"},
      {"0 0 0\n1 0 0 200\n1 1 0 3\n0 1 0 0\n3 0 1 2\n3 0 2 3\n", "fewer values"},
      {"0 0 0x 9\n1 0 0 200\n1 1 0 3\n0 1 0 0\n3 0 1 2\n3 0 2 3\n", "'0x'"},
      {"0 0 0 9.5\n1 0 0 200\n1 1 0 3\n0 1 0 0\n3 0 1 2\n3 0 2 3\n", "'9.5'"},
      {"0 0 0 9\n1 0 0 4294967296\n1 1 0 3\n0 1 0 0\n3 0 1 2\n3 0 2 3\n", "4294967296"},
      {"0 0 0 9\r1 0 0 200\n1 1 0 3\n0 1 0 0\n3 0 1 2\n3 0 2 3\n", "carriage return"},
      {good + "7\n", "after the last element"},
      {good.substr(0, good.size() - 1), "without a line end"},
  };
  for (const auto& [body, reason] : cases)
    EXPECT_NE(why(asciiPly("otherwise.ply", body)).find(reason), std::string::npos) << body;
  EXPECT_NE(refusal(asciiPly("short.ply", good.substr(0, good.find("3 0 1 2")))).find("truncated"),
            std::string::npos);
}

}  // namespace
}  // namespace lzb::sampletree
