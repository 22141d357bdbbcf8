// A binary PLY read by slices gives, slice by slice, the records a whole read gives, reads no more
// of the file than the header and its slices, and leaves to the stream what it cannot be sure to
// read alike.
#include "src/scene/ply_slices.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "tests/support/files.hpp"
#include "tests/support/ply_files.hpp"

namespace lzb {
namespace {

std::unique_ptr<PlySlices> openSlices(const std::filesystem::path& path) {
  std::string why;
  std::unique_ptr<PlySlices> s = PlySlices::open(path, why);
  EXPECT_TRUE(s) << why;
  return s;
}

// The records of [0, count) read in `cuts` slices, concatenated.
template <class Read>
void readInSlices(uint64_t count, int cuts, Read&& read) {
  for (int k = 0; k < cuts; ++k)
    read(count * uint64_t(k) / uint64_t(cuts), count * uint64_t(k + 1) / uint64_t(cuts));
}

TEST(PlySlices, SlicesGiveTheWholeReadsRecordsInEitherByteOrder) {
  const test::ScratchDir dir;
  for (const auto encoding : {test::PlyEncoding::kLittleEndian, test::PlyEncoding::kBigEndian})
    for (const bool shared : {true, false})
      for (const bool doubles : {true, false}) {
        SCOPED_TRACE(std::to_string(int(encoding)) + (shared ? " shared" : " unshared") +
                     (doubles ? " doubles" : " floats"));
        const auto path = test::triangleMesh(encoding, 0.0, 9, {shared, doubles, true})
                              .write(dir.path() / "t.ply");
        const auto whole = openSlices(path);
        ASSERT_TRUE(whole);
        EXPECT_EQ(whole->faces(), 2u * 8 * 8);
        EXPECT_EQ(whole->vertices(), shared ? 81u : 3u * whole->faces());
        EXPECT_TRUE(whole->coloured());
        std::vector<glm::vec3> positions, colours;
        std::vector<uint32_t> faces;
        whole->readVertices(0, whole->vertices(), positions, colours);
        const PlySlices::FaceRead all = whole->readFaces(0, whole->faces(), faces);
        EXPECT_EQ(all.stop, whole->faces());
        EXPECT_TRUE(all.error.empty()) << all.error;
        ASSERT_EQ(faces.size(), 3 * whole->faces());
        // The second triangle repeats its first corner (degenerate; the loaders drop it).
        EXPECT_EQ(faces[3], shared ? 0u : 3u);
        EXPECT_EQ(faces[4], shared ? 0u : 4u);
        if (shared) {
          EXPECT_TRUE(std::isnan(positions[2 + 3 * 9].x)) << "the NaN vertex";
        }
        std::vector<glm::vec3> slicedPositions, slicedColours;
        std::vector<uint32_t> slicedFaces;
        const auto sliced = openSlices(path);
        readInSlices(whole->vertices(), 4, [&](uint64_t b, uint64_t e) {
          std::vector<glm::vec3> p, c;
          sliced->readVertices(b, e, p, c);
          slicedPositions.insert(slicedPositions.end(), p.begin(), p.end());
          slicedColours.insert(slicedColours.end(), c.begin(), c.end());
        });
        readInSlices(whole->faces(), 3, [&](uint64_t b, uint64_t e) {
          EXPECT_EQ(sliced->readFaces(b, e, slicedFaces).stop, e);
        });
        EXPECT_EQ(slicedFaces, faces);
        ASSERT_EQ(slicedPositions.size(), positions.size());
        for (size_t v = 0; v < positions.size(); ++v)
          if (positions[v] == positions[v]) {
            EXPECT_EQ(slicedPositions[v], positions[v]) << v;
          }
        EXPECT_EQ(slicedColours, colours);
      }
}

TEST(PlySlices, ASliceReadsItsRecordsAndTheHeaderAlone) {
  const test::ScratchDir dir;
  const auto path =
      test::triangleMesh(test::PlyEncoding::kLittleEndian, 0.0, 300).write(dir.path() / "t.ply");
  const uint64_t size = std::filesystem::file_size(path);
  const auto s = openSlices(path);
  const uint64_t header = s->bytesRead();
  EXPECT_LE(header, uint64_t(1) << 16) << "the header in one step";
  std::vector<glm::vec3> positions, colours;
  std::vector<uint32_t> faces;
  s->readVertices(1000, 2000, positions, colours);
  EXPECT_EQ(s->bytesRead() - header, 1000u * 15) << "three floats and three bytes a vertex";
  s->readFaces(50000, 60000, faces);
  // Flags, count, three ints a face; the first face's flags may be skipped over unread.
  EXPECT_LE(s->bytesRead() - header, 1000u * 15 + 10000u * 14);
  EXPECT_GE(s->bytesRead() - header, 1000u * 15 + 10000u * 14 - 14);
  EXPECT_LT(s->bytesRead(), size / 10);
}

TEST(PlySlices, OtherFilesAreLeftToTheStream) {
  const test::ScratchDir dir;
  std::string why;
  EXPECT_FALSE(PlySlices::open(
      test::triangleMesh(test::PlyEncoding::kAscii, 0.0, 5).write(dir.path() / "a.ply"), why));
  EXPECT_EQ(why, "ASCII");
  EXPECT_FALSE(PlySlices::open(
      test::polygonMesh(test::PlyEncoding::kLittleEndian, 0.0, 5).write(dir.path() / "p.ply"),
      why));
  EXPECT_NE(why.find("of varying size"), std::string::npos) << why;
  // Cut short: the stream says where it ends.
  const auto path =
      test::triangleMesh(test::PlyEncoding::kLittleEndian, 0.0, 5).write(dir.path() / "short.ply");
  std::filesystem::resize_file(path, std::filesystem::file_size(path) - 3);
  EXPECT_FALSE(PlySlices::open(path, why));
  EXPECT_EQ(why, "data shorter than its faces as triangles");
}

// Faces of other sizes that fill the triangles' bytes (a quad and a line), and an index past the
// vertices: the reader stops at the face and says which.
TEST(PlySlices, AFaceNotATriangleOrOutOfRangeStopsTheRead) {
  const test::ScratchDir dir;
  test::PlyFile f;
  f.header =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 4\nproperty list uchar int vertex_indices\n";
  for (int v = 0; v < 4; ++v) f.put(float(v % 2)), f.put(float(v / 2)), f.put(0.0f);
  const auto face = [&](std::vector<int32_t> corners) {
    f.put(uint8_t(corners.size()));
    for (const int32_t c : corners) f.put(c);
  };
  face({0, 1, 2});
  face({0, 1, 7});
  face({0, 1, 2, 3});
  face({0, 1});
  const auto s = openSlices(f.write(dir.path() / "odd.ply"));
  std::vector<uint32_t> faces;
  const PlySlices::FaceRead bad = s->readFaces(0, 4, faces);
  EXPECT_EQ(bad.stop, 1u);
  EXPECT_FALSE(bad.notTriangle);
  EXPECT_EQ(bad.error, "malformed: face 1 uses vertex 7 of 4");
  EXPECT_EQ(faces.size(), 3u) << "the faces before it";
  const PlySlices::FaceRead quad = s->readFaces(2, 4, faces);
  EXPECT_EQ(quad.stop, 2u);
  EXPECT_TRUE(quad.notTriangle);
}

}  // namespace
}  // namespace lzb
