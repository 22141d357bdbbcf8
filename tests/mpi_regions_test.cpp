// --distribute data read in slices, on 1 to 4 ranks: the distributed cut is the serial one, the
// share each rank holds (its triangles, their IDs, its regions) is the streamed share's, each rank
// reads its slice and the header alone, and a rank that finds a malformed record in its slice, or
// is refused its share, fails every rank alike.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "mpi/collectives.hpp"
#include "mpi/decomposition.hpp"
#include "mpi/failure.hpp"
#include "mpi/group.hpp"
#include "src/core/error.hpp"
#include "src/regions/distributed_cut.hpp"
#include "src/regions/sliced_share.hpp"
#include "src/regions/streamed_share.hpp"
#include "src/scene/chunked_scene.hpp"
#include "tests/support/ply_files.hpp"
#include "tests/support/shares.hpp"

namespace lzb::regions {
namespace {

namespace fs = std::filesystem;

// One folder for every rank's files: the root writes, then every rank reads.
class SharedDir {
 public:
  explicit SharedDir(const mpi::Group& g) : g_(g) {
    path_ = mpi::broadcastString(
        g,
        (fs::temp_directory_path() / ("lzb_mpi_regions_" + std::to_string(::getpid()))).string());
    if (g.root()) fs::create_directories(path_);
    g.barrier();
  }
  ~SharedDir() {
    g_.barrier();
    std::error_code ec;
    if (g_.root()) fs::remove_all(path_, ec);
  }
  std::string write(const std::string& name, const test::PlyFile& file) const {
    if (g_.root()) file.write(fs::path(path_) / name);
    g_.barrier();
    return (fs::path(path_) / name).string();
  }

 private:
  const mpi::Group& g_;
  std::string path_;
};

TEST(DistributedCut, EqualsTheSerialCutOnAnyRankCount) {
  const mpi::Group g = mpi::Group::world();
  // Many ties on every axis (few distinct coordinates, -0 among the zeros) and a wide x.
  std::mt19937 rng(11);
  std::vector<glm::dvec3> all(5000);
  for (glm::dvec3& c : all) {
    c = {double(rng() % 40) * 3.0 - 60.0, double(rng() % 7) - 3.0, rng() % 5 ? 0.0 : -0.0};
    if (c.x == 0.0 && rng() % 2) c.x = -0.0;  // the widest axis: a cut falls among them
  }
  const IdRange mine = shareRange(all.size(), WorkShare{g.rank, g.size});
  const std::span<const glm::dvec3> local(all.data() + mine.begin, mine.end - mine.begin);
  for (const uint32_t regions : {1u, 2u, 5u, 16u, 37u}) {
    const std::vector<uint32_t> serial = splitIntoRegions(all, {}, regions);
    const RegionCut cut = cutIntoRegionsTogether(g, local, mine.begin, regions);
    // EXPECT, not ASSERT: a rank leaving the loop early would leave the others in a collective.
    EXPECT_EQ(cut.regionOf, std::vector<uint32_t>(serial.begin() + std::ptrdiff_t(mine.begin),
                                                  serial.begin() + std::ptrdiff_t(mine.end)))
        << regions << " regions";
    std::vector<uint64_t> triangles(regions, 0);
    for (const uint32_t r : serial) ++triangles[r];
    EXPECT_EQ(cut.regionTriangles, triangles);
  }
}

// The share read in slices against the streamed share of the same file, for both layouts and
// several region counts; every rank's bytes read are its slices and the header.
void expectSlicedEqualsStreamed(const mpi::Group& g, const std::string& path,
                                uint64_t chunkBytes = kExchangeChunkBytes) {
  const WorkShare share{g.rank, g.size};
  for (const Parts layout : {Parts::kOne, Parts::kPerRegion})
    for (const uint32_t regions : {1u, 5u, 16u}) {
      SCOPED_TRACE(path + ": " + std::to_string(regions) + " regions, rank " +
                   std::to_string(g.rank) + " of " + std::to_string(g.size));
      SceneOutline slicedOutline, streamedOutline;
      const std::optional<HeldShare> sliced =
          holdSlicedShare(path, g, regions, layout, true, slicedOutline, {}, chunkBytes);
      ASSERT_TRUE(sliced.has_value());
      const std::optional<ChunkedScene> chunked = openChunkedScene(path, true);
      ASSERT_TRUE(chunked.has_value());
      const HeldShare streamed =
          holdStreamedShare(*chunked, regions, share, layout, streamedOutline);
      test::expectSameOutline(slicedOutline, streamedOutline);
      test::expectSameShare(*sliced, streamed, layout);
      ASSERT_TRUE(sliced->bytesRead.has_value());
      const uint64_t size = fs::file_size(path);
      EXPECT_LE(*sliced->bytesRead, size / uint64_t(g.size) + (uint64_t(1) << 16) + 64)
          << "its slices and the header";
    }
}

TEST(SlicedShare, EqualsTheStreamedShareOfSharedAndUnsharedVertices) {
  const mpi::Group g = mpi::Group::world();
  const SharedDir dir(g);
  expectSlicedEqualsStreamed(
      g, dir.write("shared.ply", test::triangleMesh(test::PlyEncoding::kLittleEndian, 0.0, 23)));
  expectSlicedEqualsStreamed(
      g, dir.write("unshared.ply", test::triangleMesh(test::PlyEncoding::kBigEndian, 0.0, 17,
                                                      {false, true, false})));
}

TEST(SlicedShare, AFileFarFromTheOriginIsRecentredAsTheLoaderRecentresIt) {
  const mpi::Group g = mpi::Group::world();
  const SharedDir dir(g);
  expectSlicedEqualsStreamed(
      g, dir.write("far.ply", test::triangleMesh(test::PlyEncoding::kLittleEndian, 1e7, 19,
                                                 {true, true, true})));
}

TEST(SlicedShare, TheExchangeInSmallChunksGivesTheSameShare) {
  const mpi::Group g = mpi::Group::world();
  const SharedDir dir(g);
  // Three triangles a message: many rounds.
  expectSlicedEqualsStreamed(
      g, dir.write("chunks.ply", test::triangleMesh(test::PlyEncoding::kLittleEndian, 0.0, 15)),
      3 * 56);
}

TEST(SlicedShare, FilesOfOtherFacesAreLeftToTheStream) {
  const mpi::Group g = mpi::Group::world();
  const SharedDir dir(g);
  SceneOutline outline;
  EXPECT_FALSE(holdSlicedShare(
      dir.write("polygons.ply", test::polygonMesh(test::PlyEncoding::kLittleEndian, 0.0, 9)), g, 4,
      Parts::kOne, true, outline));
  EXPECT_FALSE(
      holdSlicedShare(dir.write("text.ply", test::triangleMesh(test::PlyEncoding::kAscii, 0.0, 9)),
                      g, 4, Parts::kOne, true, outline));
}

// A file of `faces` triangles over a 2 x 2 grid whose face `at` is given by `odd` instead.
test::PlyFile fileWithFace(int faces, int at, const std::vector<int32_t>& odd,
                           const std::vector<int32_t>& next = {}) {
  test::PlyFile f;
  f.header =
      "element vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face " +
      std::to_string(faces) + "\nproperty list uchar int vertex_indices\n";
  for (int v = 0; v < 4; ++v) f.put(float(v % 2)), f.put(float(v / 2)), f.put(0.0f);
  for (int t = 0; t < faces; ++t) {
    std::vector<int32_t> corners =
        t % 2 ? std::vector<int32_t>{1, 3, 2} : std::vector<int32_t>{0, 1, 2};
    if (t == at) corners = odd;
    if (t == at + 1 && !next.empty()) corners = next;
    f.put(uint8_t(corners.size()));
    for (const int32_t c : corners) f.put(c);
  }
  return f;
}

TEST(SlicedShare, AMalformedFaceInOneSliceFailsEveryRankWithOneMessage) {
  const mpi::Group g = mpi::Group::world();
  const SharedDir dir(g);
  SceneOutline outline;
  // The last face (the last rank's slice) uses a vertex past the four.
  const std::string bad = dir.write("bad.ply", fileWithFace(40, 39, {0, 1, 9}));
  try {
    holdSlicedShare(bad, g, 4, Parts::kOne, true, outline);
    ADD_FAILURE() << "rank " << g.rank << " went on";
  } catch (const mpi::JobFailed& e) {
    EXPECT_EQ(e.status, 2) << "bad input";
  }
  // A quad and a line filling two triangles' bytes before it: the records after them are
  // misread, so the file goes to the stream (which names what is wrong) on every rank.
  const std::string odd = dir.write("odd.ply", fileWithFace(40, 2, {0, 1, 2, 3}, {0, 1}));
  EXPECT_FALSE(holdSlicedShare(odd, g, 4, Parts::kOne, true, outline));
}

TEST(SlicedShare, AShareRefusedOnOneRankFailsEveryRank) {
  const mpi::Group g = mpi::Group::world();
  const SharedDir dir(g);
  const std::string path =
      dir.write("t.ply", test::triangleMesh(test::PlyEncoding::kLittleEndian, 0.0, 9));
  SceneOutline outline;
  const auto refuseOnLast = [&](const HeldShare&) {
    require(g.rank != g.size - 1, path, "refused");
  };
  EXPECT_THROW(holdSlicedShare(path, g, 4, Parts::kOne, true, outline, refuseOnLast),
               mpi::JobFailed);
}

}  // namespace
}  // namespace lzb::regions
