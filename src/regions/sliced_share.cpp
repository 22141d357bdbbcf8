#include "src/regions/sliced_share.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <span>
#include <vector>

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

void allreduce(const mpi::Group& g, void* data, size_t n, MPI_Datatype type, MPI_Op op) {
  if (n) LZB_MPI_CALL(MPI_Allreduce(MPI_IN_PLACE, data, int(n), type, op, g.comm));
}

// The rank whose shareRange of `count` items holds item i.
int holderOf(uint64_t i, uint64_t count, int size) {
  const uint64_t q = count / uint64_t(size), r = count % uint64_t(size);
  if (i < r * (q + 1)) return int(i / (q + 1));
  return int(r + (i - r * (q + 1)) / q);
}

// Sends counts[r] items of `send` (grouped by rank, in rank order) to each rank r and returns
// what each rank sent this one, in rank order: messages of at most chunkBytes a pair and round,
// each from its own address, so no count or displacement passes 32 bits.
template <class T>
std::vector<T> exchange(const mpi::Group& g, std::span<const T> send,
                        const std::vector<uint64_t>& counts, uint64_t chunkBytes,
                        std::vector<uint64_t>* received = nullptr) {
  const size_t n = size_t(g.size);
  std::vector<uint64_t> recvCounts(n);
  LZB_MPI_CALL(
      MPI_Alltoall(counts.data(), 1, MPI_UINT64_T, recvCounts.data(), 1, MPI_UINT64_T, g.comm));
  std::vector<uint64_t> sendAt(n, 0), recvAt(n, 0);
  for (size_t r = 1; r < n; ++r) {
    sendAt[r] = sendAt[r - 1] + counts[r - 1];
    recvAt[r] = recvAt[r - 1] + recvCounts[r - 1];
  }
  std::vector<T> recv(size_t(recvAt[n - 1] + recvCounts[n - 1]));
  const uint64_t chunk =
      std::max<uint64_t>(1, std::min<uint64_t>(chunkBytes, INT32_MAX) / sizeof(T));
  std::vector<MPI_Request> requests;
  for (uint64_t done = 0;; done += chunk) {
    requests.clear();
    for (size_t r = 0; r < n; ++r) {
      if (recvCounts[r] > done)
        LZB_MPI_CALL(MPI_Irecv(recv.data() + recvAt[r] + done,
                               int(std::min(chunk, recvCounts[r] - done) * sizeof(T)), MPI_BYTE,
                               int(r), kExchangeTag, g.comm, &requests.emplace_back()));
      if (counts[r] > done)
        LZB_MPI_CALL(MPI_Isend(send.data() + sendAt[r] + done,
                               int(std::min(chunk, counts[r] - done) * sizeof(T)), MPI_BYTE, int(r),
                               kExchangeTag, g.comm, &requests.emplace_back()));
    }
    if (requests.empty()) {
      if (received) *received = std::move(recvCounts);
      return recv;
    }
    LZB_MPI_CALL(MPI_Waitall(int(requests.size()), requests.data(), MPI_STATUSES_IGNORE));
  }
}

// `text` of rank `from`, on every rank.
std::string broadcastFrom(const mpi::Group& g, int from, std::string text) {
  uint64_t size = text.size();
  LZB_MPI_CALL(MPI_Bcast(&size, 1, MPI_UINT64_T, from, g.comm));
  text.resize(size_t(size));
  LZB_MPI_CALL(MPI_Bcast(text.data(), int(size), MPI_CHAR, from, g.comm));
  return text;
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
  allreduce(g, first, 2, MPI_UINT64_T, MPI_MIN);
  if (first[0] != ~uint64_t(0)) return false;
  if (first[1] == ~uint64_t(0)) return true;
  const std::string error = broadcastFrom(g, holderOf(first[1], file.faces(), g.size), read.error);
  mpi::agree(g, [&] { throw InputError(file.where() + ": " + error); });
  return false;
}

// The stored frame of the whole file, from the bounds of every rank's finite vertices.
HeldVertices storedFrame(const mpi::Group& g, const Slice& slice) {
  double box[6];
  std::fill(box, box + 6, std::numeric_limits<double>::max());
  for (const glm::vec3& v : slice.positions) {
    const glm::dvec3 p = storedVertex(glm::dmat4(1.0), v.x, v.y, v.z, glm::dvec3(0.0));
    if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) continue;
    for (int k = 0; k < 3; ++k)
      box[k] = std::min(box[k], p[k]), box[3 + k] = std::min(box[3 + k], -p[k]);
  }
  allreduce(g, box, 6, MPI_DOUBLE, MPI_MIN);
  Bounds finite;
  if (box[0] <= -box[3]) finite = Bounds{{box[0], box[1], box[2]}, {-box[3], -box[4], -box[5]}};
  HeldVertices frame;
  frame.place(finite);
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
  for (const uint32_t v : needed) ++asks[size_t(holderOf(v, vertexCount, g.size))];
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

// The local triangles packed by the rank holding their region (rank order, IDs rising in each).
std::vector<Travelling> pack(const Mesh& mesh, uint64_t firstId, const RegionCut& cut,
                             const std::vector<int>& owner, std::vector<uint64_t>& counts) {
  std::vector<uint64_t> at(counts.size(), 0);
  for (const uint32_t r : cut.regionOf) ++counts[size_t(owner[r])];
  for (size_t r = 1; r < at.size(); ++r) at[r] = at[r - 1] + counts[r - 1];
  std::vector<Travelling> out(mesh.size());
  for (size_t t = 0; t < mesh.size(); ++t) {
    const uint32_t region = cut.regionOf[t];
    out[at[size_t(owner[region])]++] = {firstId + t,
                                        region,
                                        mesh.color(t),
                                        {mesh.vertex(t, 0), mesh.vertex(t, 1), mesh.vertex(t, 2)}};
  }
  return out;
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

}  // namespace

uint64_t slicedLoadBytes(uint64_t faces, int ranks) {
  return kSlicedLoadBytesPerFace * (faces / uint64_t(ranks) + 1);
}

namespace {

bool plyExtension(const std::string& path) {
  const std::string ext = std::filesystem::path(path).extension().string();
  return ext == ".ply" || ext == ".PLY";
}

}  // namespace

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
  Slice slice;
  if (!readSlice(group, *file, slice)) return std::nullopt;
  HeldVertices frame = storedFrame(group, slice);
  fetchVertices(group, file->vertices(), chunkBytes, slice, frame);
  LoadStats stats;
  Mesh mesh = trianglesOf(slice, frame, stats);
  slice = Slice();
  frame.positions = {}, frame.colours = {};
  // The outline from all ranks' counts and boxes, the IDs from the counts before this rank's.
  uint64_t firstId = 0, kept = mesh.size();
  LZB_MPI_CALL(MPI_Exscan(&kept, &firstId, 1, MPI_UINT64_T, MPI_SUM, group.comm));
  if (group.rank == 0) firstId = 0;
  uint64_t counts[3] = {stats.loaded, stats.degenerate, stats.nonFinite};
  allreduce(group, counts, 3, MPI_UINT64_T, MPI_SUM);
  stats = {counts[0], counts[1], counts[2]};
  require(stats.loaded > 0, file->where(),
          "no valid triangles (" + std::to_string(stats.degenerate) + " degenerate, " +
              std::to_string(stats.nonFinite) + " non-finite dropped)");
  if (!quiet && group.root()) warnDropped(path, stats);
  double box[6];
  std::fill(box, box + 6, std::numeric_limits<double>::max());
  for (const glm::vec3& p : mesh.positions)
    for (int k = 0; k < 3; ++k)
      box[k] = std::min(box[k], double(p[k])), box[3 + k] = std::min(box[3 + k], -double(p[k]));
  allreduce(group, box, 6, MPI_DOUBLE, MPI_MIN);
  const Bounds nodeBox{{box[0], box[1], box[2]}, {-box[3], -box[4], -box[5]}};
  SceneOutline base;
  base.source = path;
  outline = placedMeshOutline(base, nodeBox, frame.placement, stats.loaded, stats);

  HeldShare held;
  held.regions = regionCount(regions, stats.loaded, layout == Parts::kOne);
  held.units = stats.loaded;
  RegionCut cut;
  {
    std::vector<glm::dvec3> centres(mesh.size());
    for (size_t t = 0; t < mesh.size(); ++t) centres[t] = placedCentroid(mesh, t, frame.placement);
    cut = cutIntoRegionsTogether(group, centres, firstId, held.regions);
  }
  dealRegions(cut.regionTriangles, held, WorkShare{group.rank, group.size}, layout);
  if (beforeKeeping) mpi::agree(group, [&] { beforeKeeping(held); });
  std::vector<uint64_t> sendCounts(size_t(group.size), 0);
  std::vector<Travelling> arrived;
  {
    const std::vector<Travelling> leaving =
        pack(mesh, firstId, cut, regionOwners(cut.regionTriangles, group.size), sendCounts);
    mesh = Mesh(), cut = RegionCut();
    arrived = exchange<Travelling>(group, leaving, sendCounts, chunkBytes);
  }
  held.parts.resize(partCount(held, layout));
  uint32_t meshNode = 0;
  for (ScenePart& part : held.parts) meshNode = startMeshPart(outline, frame.placement, part.scene);
  keepArrived(arrived, held, meshNode, held.parts);
  arrived = {};
  for (ScenePart& part : held.parts) finishMeshPart(outline, meshNode, nodeBox, part.scene);
  held.bytesRead = file->bytesRead();
  return held;
}

}  // namespace lzb::regions
