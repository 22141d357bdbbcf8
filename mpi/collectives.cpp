#include "mpi/collectives.hpp"

namespace lzb::mpi {

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
