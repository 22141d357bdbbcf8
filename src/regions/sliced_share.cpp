#include "src/regions/sliced_share.hpp"

#include <malloc.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <memory>
#include <span>
#include <vector>

#include "mpi/collectives.hpp"
#include "mpi/decomposition.hpp"
#include "mpi/failure.hpp"
#include "src/core/error.hpp"
#include "src/regions/distributed_cut.hpp"
#include "src/regions/memory_estimate.hpp"
#include "src/scene/load.hpp"
#include "src/scene/mesh_builder.hpp"
#include "src/scene/mesh_stream.hpp"
#include "src/scene/ply_slices.hpp"

namespace lzb::regions {

namespace {

constexpr int kExchangeTag = 4242;

// The pages of buffers freed since, handed back to the system: glibc keeps them for the next
// allocation, so a step's buffers would stay in the rank's peak through the steps after it.
void handBackFreedPages() {
#ifdef __GLIBC__
  malloc_trim(0);
#endif
}

bool plyExtension(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".ply" || ext == ".PLY";
}

// Writes items [first, first + count) of those this rank sends rank `to` into `out`.
template <class T>
using Packer = std::function<void(size_t to, uint64_t first, uint64_t count, T* out)>;

// Sends counts[r] items to each rank r, packed round by round, and returns what each rank sent
// this one, in rank order. A round sends each rank at most chunkBytes, and at most
// kExchangeRoundBytes in all, each message from its own buffer, so neither a count nor the send
// buffers grow with the share: what leaves is never held whole.
template <class T>
std::vector<T> exchange(const mpi::Group& g, const std::vector<uint64_t>& counts,
                        uint64_t chunkBytes, const Packer<T>& pack,
                        std::vector<uint64_t>* received = nullptr) {
  const size_t n = size_t(g.size);
  std::vector<uint64_t> recvCounts(n);
  LZB_MPI_CALL(
      MPI_Alltoall(counts.data(), 1, MPI_UINT64_T, recvCounts.data(), 1, MPI_UINT64_T, g.comm));
  std::vector<uint64_t> recvAt(n, 0);
  for (size_t r = 1; r < n; ++r) recvAt[r] = recvAt[r - 1] + recvCounts[r - 1];
  std::vector<T> recv(size_t(recvAt[n - 1] + recvCounts[n - 1]));
  const uint64_t pairBytes = std::min({chunkBytes, kExchangeRoundBytes / n, uint64_t(INT32_MAX)});
  const uint64_t chunk = std::max<uint64_t>(1, pairBytes / sizeof(T));
  std::vector<std::vector<T>> outbox(n);
  std::vector<MPI_Request> requests;
  for (uint64_t done = 0;; done += chunk) {
    requests.clear();
    for (size_t r = 0; r < n; ++r) {
      if (recvCounts[r] > done)
        LZB_MPI_CALL(MPI_Irecv(recv.data() + recvAt[r] + done,
                               int(std::min(chunk, recvCounts[r] - done) * sizeof(T)), MPI_BYTE,
                               int(r), kExchangeTag, g.comm, &requests.emplace_back()));
      if (counts[r] > done) {
        outbox[r].resize(size_t(std::min(chunk, counts[r] - done)));
        pack(r, done, outbox[r].size(), outbox[r].data());
        LZB_MPI_CALL(MPI_Isend(outbox[r].data(), int(outbox[r].size() * sizeof(T)), MPI_BYTE,
                               int(r), kExchangeTag, g.comm, &requests.emplace_back()));
      }
    }
    if (requests.empty()) {
      if (received) *received = std::move(recvCounts);
      return recv;
    }
    LZB_MPI_CALL(MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE));
  }
}

// exchange() of items held in `send`, grouped by rank in rank order.
template <class T>
std::vector<T> exchange(const mpi::Group& g, std::span<const T> send,
                        const std::vector<uint64_t>& counts, uint64_t chunkBytes,
                        std::vector<uint64_t>* received = nullptr) {
  std::vector<uint64_t> sendAt(counts.size(), 0);
  for (size_t r = 1; r < counts.size(); ++r) sendAt[r] = sendAt[r - 1] + counts[r - 1];
  const Packer<T> copy = [&](size_t to, uint64_t first, uint64_t count, T* out) {
    std::copy_n(send.begin() + std::ptrdiff_t(sendAt[to] + first), count, out);
  };
  return exchange<T>(g, counts, chunkBytes, copy, received);
}

// A rank's slice of the file: its vertex records and the faces of its face records.
struct Slice {
  uint64_t firstVertex = 0;
  std::vector<glm::vec3> positions, colours;  // of vertices [firstVertex, ...)
  std::vector<uint32_t> faces;                // three vertex indices a face
};

// Reads this rank's slice. The first malformed face over all ranks fails every rank with the one
// message the stream gives, unless a face before it, on any rank, is other than a triangle (the
// records after one are misread). Returns false (on every rank) when some face is not a
// triangle: the file is not read in slices.
bool readSlice(const mpi::Group& g, PlySlices& file, Slice& slice) {
  const WorkShare share{g.rank, g.size};
  const IdRange vertices = shareRange(file.vertices(), share);
  const IdRange faces = shareRange(file.faces(), share);
  PlySlices::FaceRead read;
  mpi::agree(g, [&] {
    slice.firstVertex = vertices.begin;
    file.readVertices(vertices.begin, vertices.end, slice.positions, slice.colours);
    read = file.readFaces(faces.begin, faces.end, slice.faces);
  });
  const bool stopped = read.stop < faces.end;
  uint64_t first[2] = {stopped && read.notTriangle ? read.stop : ~uint64_t(0),
                       stopped && !read.notTriangle ? read.stop : ~uint64_t(0)};
  mpi::allreduceInPlace(g, first, 2, MPI_UINT64_T, MPI_MIN);
  if (first[0] != ~uint64_t(0)) return false;
  if (first[1] == ~uint64_t(0)) return true;
  const std::string error =
      mpi::broadcastString(g, read.error, shareRankOf(first[1], file.faces(), g.size));
  mpi::agree(g, [&] { throw InputError(file.where() + ": " + error); });
  return false;
}

// The stored frame of the whole file, from the bounds of every rank's finite vertices.
HeldVertices storedFrame(const mpi::Group& g, const Slice& slice) {
  Bounds finite;
  for (const glm::vec3& v : slice.positions) {
    const glm::dvec3 p = storedVertex(glm::dmat4(1.0), v.x, v.y, v.z, glm::dvec3(0.0));
    if (std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.z)) finite.extend(p);
  }
  HeldVertices frame;
  frame.place(mpi::boundsOverRanks(g, finite));
  return frame;
}

// The vertices this rank's faces use, fetched from the ranks that read them, in `frame` (its
// positions and colours indexed by the faces' indices, remapped in place).
void fetchVertices(const mpi::Group& g, uint64_t vertexCount, uint64_t chunkBytes, Slice& slice,
                   HeldVertices& frame) {
  std::vector<uint32_t> needed(slice.faces);
  std::sort(needed.begin(), needed.end());
  needed.erase(std::unique(needed.begin(), needed.end()), needed.end());
  needed.shrink_to_fit();
  std::vector<uint64_t> asks(size_t(g.size), 0);
  for (const uint32_t v : needed) ++asks[size_t(shareRankOf(v, vertexCount, g.size))];
  std::vector<uint64_t> answerCounts;  // what each rank asked of this one
  const std::vector<uint32_t> asked =
      exchange<uint32_t>(g, needed, asks, chunkBytes, &answerCounts);
  // Answer in the order asked: positions, then colours when the file has them.
  const size_t stride = slice.colours.empty() ? 1 : 2;
  std::vector<glm::vec3> answers;
  answers.reserve(asked.size() * stride);
  for (const uint32_t v : asked) {
    answers.push_back(slice.positions[v - slice.firstVertex]);
    if (stride == 2) answers.push_back(slice.colours[v - slice.firstVertex]);
  }
  for (uint64_t& count : answerCounts) count *= stride;
  slice.positions = {}, slice.colours = {};
  const std::vector<glm::vec3> got = exchange<glm::vec3>(g, answers, answerCounts, chunkBytes);
  frame.positions.resize(needed.size());
  if (stride == 2) frame.colours.resize(needed.size());
  for (size_t i = 0; i < needed.size(); ++i) {
    frame.positions[i] = got[stride * i];
    if (stride == 2) frame.colours[i] = got[stride * i + 1];
  }
  for (uint32_t& v : slice.faces)
    v = uint32_t(std::lower_bound(needed.begin(), needed.end(), v) - needed.begin());
}

// This rank's faces made into triangles as the loader makes them, in file order.
Mesh trianglesOf(const Slice& slice, const HeldVertices& frame, LoadStats& stats) {
  const std::function<void(const Mesh&)> none = [](const Mesh&) {};
  FaceChunks faces(frame, none, ~size_t(0));
  std::vector<uint32_t> face(3);
  for (size_t f = 0; f < slice.faces.size(); f += 3) {
    std::copy_n(slice.faces.begin() + std::ptrdiff_t(f), 3, face.begin());
    faces.face(face);
  }
  Mesh mesh = faces.take();
  stats = faces.finish();
  return mesh;
}

// A triangle on its way to the rank holding its region.
struct Travelling {
  uint64_t id;
  uint32_t region;
  Rgba8 colour;
  glm::vec3 corner[3];  // stored frame
};

// The local triangles grouped by the rank holding their region (rank order, IDs rising in each),
// and how many go to each rank.
std::vector<uint32_t> byHolder(const RegionCut& cut, const std::vector<int>& owner,
                               std::vector<uint64_t>& counts) {
  std::vector<uint64_t> at(counts.size(), 0);
  for (const uint32_t r : cut.regionOf) ++counts[size_t(owner[r])];
  for (size_t r = 1; r < at.size(); ++r) at[r] = at[r - 1] + counts[r - 1];
  std::vector<uint32_t> order(cut.regionOf.size());
  for (uint32_t t = 0; t < order.size(); ++t) order[at[size_t(owner[cut.regionOf[t]])]++] = t;
  return order;
}

// The received triangles (ID order) kept in the parts of their regions.
void keepArrived(const std::vector<Travelling>& arrived, const HeldShare& held, uint32_t meshNode,
                 std::vector<ScenePart>& parts) {
  const std::vector<uint32_t> partOf = partOfRegion(held);
  std::vector<LoadStats> counted(parts.size());
  std::vector<MeshBuilder> builders;
  builders.reserve(parts.size());
  for (size_t p = 0; p < parts.size(); ++p)
    builders.emplace_back(parts[p].scene.nodes[meshNode].mesh, counted[p]);
  for (const Travelling& t : arrived) {
    const uint32_t p = partOf[t.region];
    // Kept before it travelled, so kept again: the same floats, shared as the loader shares them.
    builders[p].triangle(glm::dvec3(t.corner[0]), glm::dvec3(t.corner[1]), glm::dvec3(t.corner[2]),
                         t.colour);
    parts[p].ids.add(t.id, 1);
    ++parts[p].units;
  }
}

// This rank's triangles of the file read in slices, in the stored frame.
struct LocalTriangles {
  Mesh mesh;                  // in file order
  uint64_t firstId = 0;       // the whole scene's ID of the first
  glm::dmat4 placement{1.0};  // stored frame -> world
  Bounds nodeBox;             // the stored frame's box of every rank's triangles
};

// Steps 1 and 2: the slices read, the vertices fetched, the triangles made; the outline from every
// rank's counts and boxes. nullopt (on every rank) when the file is not read in slices.
std::optional<LocalTriangles> makeTriangles(const mpi::Group& group, PlySlices& file,
                                            uint64_t chunkBytes, bool quiet,
                                            SceneOutline& outline) {
  LocalTriangles local;
  LoadStats stats;
  {
    Slice slice;
    if (!readSlice(group, file, slice)) return std::nullopt;
    HeldVertices frame = storedFrame(group, slice);
    fetchVertices(group, file.vertices(), chunkBytes, slice, frame);
    local.mesh = trianglesOf(slice, frame, stats);
    local.placement = frame.placement;
  }
  const uint64_t kept = local.mesh.size();
  LZB_MPI_CALL(MPI_Exscan(&kept, &local.firstId, 1, MPI_UINT64_T, MPI_SUM, group.comm));
  if (group.root()) local.firstId = 0;  // MPI_Exscan leaves rank 0's undefined
  uint64_t counts[3] = {stats.loaded, stats.degenerate, stats.nonFinite};
  mpi::allreduceInPlace(group, counts, 3, MPI_UINT64_T, MPI_SUM);
  stats = {counts[0], counts[1], counts[2]};
  require(stats.loaded > 0, file.where(),
          "no valid triangles (" + std::to_string(stats.degenerate) + " degenerate, " +
              std::to_string(stats.nonFinite) + " non-finite dropped)");
  if (!quiet && group.root()) warnDropped(file.where(), stats);
  Bounds stored;  // the node's own box: the kept triangles' vertices
  for (const glm::vec3& p : local.mesh.positions) stored.extend(glm::dvec3(p));
  local.nodeBox = mpi::boundsOverRanks(group, stored);
  SceneOutline base;
  base.source = file.where();
  outline = placedMeshOutline(base, local.nodeBox, local.placement, stats.loaded, stats);
  return local;
}

// Step 3: the regions cut from every rank's centres and dealt (held.regions set).
RegionCut cutAndDeal(const mpi::Group& group, const LocalTriangles& local, Parts layout,
                     HeldShare& held) {
  std::vector<glm::dvec3> centres(local.mesh.size());
  for (size_t t = 0; t < centres.size(); ++t)
    centres[t] = placedCentroid(local.mesh, t, local.placement);
  RegionCut cut = cutIntoRegionsTogether(group, centres, local.firstId, held.regions);
  dealRegions(cut.regionTriangles, held, WorkShare{group.rank, group.size}, layout);
  return cut;
}

// Step 4: each triangle sent to the rank holding its region, the arrivals kept in this rank's
// parts; what was sent and received is freed before the parts are finished.
void exchangeAndKeep(const mpi::Group& group, LocalTriangles& local, RegionCut& cut,
                     const SceneOutline& outline, uint64_t chunkBytes, HeldShare& held) {
  std::vector<uint64_t> sendCounts(size_t(group.size), 0);
  std::vector<Travelling> arrived;
  {
    const std::vector<uint32_t> order =
        byHolder(cut, regionOwners(cut.regionTriangles, group.size), sendCounts);
    std::vector<uint64_t> sendAt(sendCounts.size(), 0);
    for (size_t r = 1; r < sendAt.size(); ++r) sendAt[r] = sendAt[r - 1] + sendCounts[r - 1];
    const Mesh& mesh = local.mesh;
    const Packer<Travelling> pack = [&](size_t to, uint64_t first, uint64_t count,
                                        Travelling* out) {
      for (uint64_t k = 0; k < count; ++k) {
        const uint32_t t = order[sendAt[to] + first + k];
        out[k] = {local.firstId + t,
                  cut.regionOf[t],
                  mesh.color(t),
                  {mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2)}};
      }
    };
    arrived = exchange<Travelling>(group, sendCounts, chunkBytes, pack);
  }
  local.mesh = Mesh(), cut = RegionCut();
  held.parts.resize(partCount(held, held.layout));
  uint32_t meshNode = 0;
  for (ScenePart& part : held.parts) meshNode = startMeshPart(outline, local.placement, part.scene);
  keepArrived(arrived, held, meshNode, held.parts);
  arrived = {};
  for (ScenePart& part : held.parts) finishMeshPart(outline, meshNode, local.nodeBox, part.scene);
}

}  // namespace

uint64_t slicedLoadBytes(uint64_t faces, int ranks) {
  return kSlicedLoadBytesPerFace * (faces / uint64_t(ranks) + 1);
}

std::optional<uint64_t> slicedFaces(const std::string& path) {
  if (!plyExtension(path)) return std::nullopt;
  std::string why;
  const std::unique_ptr<PlySlices> file = PlySlices::open(path, why);
  return file ? std::optional<uint64_t>(file->faces()) : std::nullopt;
}

std::optional<HeldShare> holdSlicedShare(const std::string& path, const mpi::Group& group,
                                         uint32_t regions, Parts layout, bool quiet,
                                         SceneOutline& outline,
                                         const std::function<void(const HeldShare&)>& beforeKeeping,
                                         uint64_t chunkBytes) {
  if (!plyExtension(path)) return std::nullopt;
  std::unique_ptr<PlySlices> file;
  std::string why;
  mpi::agree(group, [&] {
    file = PlySlices::open(path, why);
    if (file)
      requireEstimate(slicedLoadBytes(file->faces(), group.size), path,
                      "reading a slice of the file (--distribute data)",
                      ": more ranks read smaller slices");
  });
  if (!file) return std::nullopt;
  std::optional<LocalTriangles> local = makeTriangles(group, *file, chunkBytes, quiet, outline);
  if (!local) return std::nullopt;
  HeldShare held;
  held.regions = regionCount(regions, outline.uniqueTriangles, layout == Parts::kOne);
  held.units = outline.uniqueTriangles;
  handBackFreedPages();
  RegionCut cut = cutAndDeal(group, *local, layout, held);
  handBackFreedPages();
  if (beforeKeeping) mpi::agree(group, [&] { beforeKeeping(held); });
  exchangeAndKeep(group, *local, cut, outline, chunkBytes, held);
  handBackFreedPages();
  held.bytesRead = file->bytesRead();
  return held;
}

}  // namespace lzb::regions
