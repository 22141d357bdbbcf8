#include "mpi/collectives.hpp"

#include <cstdint>

namespace lzb::mpi {

std::vector<std::string> gatherStrings(const Group& g, const std::string& mine) {
  int length = int(mine.size());
  std::vector<int> lengths(size_t(g.size)), offsets(size_t(g.size));
  LZB_MPI_CALL(MPI_Gather(&length, 1, MPI_INT, lengths.data(), 1, MPI_INT, 0, g.comm));
  int total = 0;
  for (int r = 0; r < g.size; ++r) offsets[size_t(r)] = total, total += lengths[size_t(r)];
  std::string all(g.root() ? size_t(total) : 0, '\0');
  LZB_MPI_CALL(MPI_Gatherv(mine.data(), length, MPI_CHAR, all.data(), lengths.data(),
                           offsets.data(), MPI_CHAR, 0, g.comm));
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

std::string broadcastString(const Group& g, const std::string& value, int from) {
  uint64_t length = value.size();
  LZB_MPI_CALL(MPI_Bcast(&length, 1, MPI_UINT64_T, from, g.comm));
  std::string out = g.rank == from ? value : std::string(size_t(length), '\0');
  LZB_MPI_CALL(MPI_Bcast(out.data(), int(length), MPI_CHAR, from, g.comm));
  return out;
}

void allreduceInPlace(const Group& g, void* data, size_t n, MPI_Datatype type, MPI_Op op) {
  if (n) LZB_MPI_CALL(MPI_Allreduce(MPI_IN_PLACE, data, int(n), type, op, g.comm));
}

void boundsOverRanks(const Group& g, std::span<Bounds> boxes) {
  // The least of each low corner and of each high corner negated.
  std::vector<double> v;
  v.reserve(6 * boxes.size());
  for (const Bounds& b : boxes)
    v.insert(v.end(), {b.lo.x, b.lo.y, b.lo.z, -b.hi.x, -b.hi.y, -b.hi.z});
  allreduceInPlace(g, v.data(), v.size(), MPI_DOUBLE, MPI_MIN);
  for (size_t i = 0; i < boxes.size(); ++i) {
    const double* b = &v[6 * i];
    boxes[i].lo = {b[0], b[1], b[2]};
    boxes[i].hi = {-b[3], -b[4], -b[5]};
  }
}

Bounds boundsOverRanks(const Group& g, Bounds box) {
  boundsOverRanks(g, std::span<Bounds>(&box, 1));
  return box;
}

}  // namespace lzb::mpi
