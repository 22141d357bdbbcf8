#include "mpi/composite.hpp"

#include <cstring>

#include "src/core/timer.hpp"

namespace lzb::mpi {

namespace {

// One pixel as it travels between ranks.
struct Pixel {
  float depth;
  Rgba8 color;
  uint64_t id;
};
static_assert(sizeof(Pixel) == 16);

void nearerOp(void* in, void* inout, int* len, MPI_Datatype*) {
  const Pixel* a = static_cast<const Pixel*>(in);
  Pixel* b = static_cast<Pixel*>(inout);
  for (int i = 0; i < *len; ++i)
    if (nearer(a[i].depth, a[i].id, b[i].depth, b[i].id)) b[i] = a[i];
}

}  // namespace

CompositeStats compositeAtRoot(const Group& g, Framebuffer& fb) {
  CompositeStats stats;
  if (g.size == 1) return stats;
  Stopwatch clock;
  const size_t n = fb.size();
  std::vector<Pixel> mine(n), result(g.root() ? n : 0);
#pragma omp parallel for schedule(static)
  for (size_t i = 0; i < n; ++i) mine[i] = Pixel{fb.depth[i], fb.color[i], fb.id[i]};

  MPI_Datatype type;
  LZB_MPI_CALL(MPI_Type_contiguous(sizeof(Pixel), MPI_BYTE, &type));
  LZB_MPI_CALL(MPI_Type_commit(&type));
  MPI_Op op;
  LZB_MPI_CALL(MPI_Op_create(&nearerOp, /*commute=*/1, &op));
  // Reduce in chunks: MPI counts are int, and chunks keep the temporary buffers bounded.
  const size_t chunk = size_t(1) << 24;
  for (size_t start = 0; start < n; start += chunk) {
    const int count = int(std::min(chunk, n - start));
    LZB_MPI_CALL(MPI_Reduce(mine.data() + start, g.root() ? result.data() + start : nullptr, count,
                            type, op, 0, g.comm));
  }
  MPI_Op_free(&op);
  MPI_Type_free(&type);
  if (g.root()) {
#pragma omp parallel for schedule(static)
    for (size_t i = 0; i < n; ++i) {
      fb.depth[i] = result[i].depth;
      fb.color[i] = result[i].color;
      fb.id[i] = result[i].id;
    }
  } else {
    stats.bytesSent = double(n * sizeof(Pixel));
  }
  stats.seconds = clock.seconds();
  return stats;
}

std::vector<std::string> gatherStrings(const Group& g, const std::string& mine) {
  int length = int(mine.size());
  std::vector<int> lengths(size_t(g.size)), offsets(size_t(g.size));
  LZB_MPI_CALL(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, g.comm));
  int total = 0;
  for (int r = 0; r < g.size; ++r) offsets[size_t(r)] = total, total += lengths[size_t(r)];
  std::string all(g.root() ? size_t(total) : 0, '\0');
  LZB_MPI_CALL(MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(), offsets.data(),
                           MPI_CHAR, 0, g.comm));
  std::vector<std::string> out;
  if (g.root())
    for (int r = 0; r < g.size; ++r)
      out.push_back(all.substr(size_t(offsets[size_t(r)]), size_t(lengths[size_t(r)])));
  return out;
}

bool broadcastFlag(const Group& g, bool value) {
  int v = value ? 1 : 0;
  LZB_MPI_CALL(MPI_Bcast(&v, 1, MPI_INT, 0, g.comm));
  return v != 0;
}

std::string broadcastString(const Group& g, const std::string& value) {
  int length = int(value.size());
  LZB_MPI_CALL(MPI_Bcast(&length, 1, MPI_INT, 0, g.comm));
  std::string out = g.root() ? value : std::string(size_t(length), '\0');
  LZB_MPI_CALL(MPI_Bcast(out.data(), length, MPI_CHAR, 0, g.comm));
  return out;
}

}  // namespace lzb::mpi
