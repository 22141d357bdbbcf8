#include "src/cli/frame_transfer.hpp"

#include <string>
#include <vector>

namespace lzb {

namespace {

constexpr int kTag = 7;

template <class T>
void sendVector(const mpi::Group& g, int to, const std::vector<T>& v) {
  const uint64_t bytes = v.size() * sizeof(T);
  LZB_MPI_CALL(MPI_Send(&bytes, 1, MPI_UINT64_T, to, kTag, g.comm));
  // MPI counts are int: large frames go in pieces.
  const char* p = reinterpret_cast<const char*>(v.data());
  for (uint64_t at = 0; at < bytes; at += 1u << 30)
    LZB_MPI_CALL(MPI_Send(p + at, int(std::min<uint64_t>(bytes - at, 1u << 30)), MPI_BYTE, to,
                          kTag, g.comm));
}

template <class T>
void receiveVector(const mpi::Group& g, int from, std::vector<T>& v) {
  uint64_t bytes = 0;
  LZB_MPI_CALL(MPI_Recv(&bytes, 1, MPI_UINT64_T, from, kTag, g.comm, MPI_STATUS_IGNORE));
  v.resize(bytes / sizeof(T));
  char* p = reinterpret_cast<char*>(v.data());
  for (uint64_t at = 0; at < bytes; at += 1u << 30)
    LZB_MPI_CALL(MPI_Recv(p + at, int(std::min<uint64_t>(bytes - at, 1u << 30)), MPI_BYTE, from,
                          kTag, g.comm, MPI_STATUS_IGNORE));
}

}  // namespace

void sendFrame(const mpi::Group& world, int to, const FrameResult& f) {
  const std::string entry = f.entry.dump();
  const std::vector<int> sizes = {f.image.width, f.image.height, f.own.width, f.own.height};
  sendVector(world, to, sizes);
  sendVector(world, to, std::vector<char>(entry.begin(), entry.end()));
  sendVector(world, to, f.image.depth);
  sendVector(world, to, f.image.color);
  sendVector(world, to, f.image.id);
  sendVector(world, to, f.own.centreId);
  sendVector(world, to, f.own.subsampleId);
  sendVector(world, to, f.own.boxColor);
}

FrameResult receiveFrame(const mpi::Group& world, int from) {
  FrameResult f;
  std::vector<int> sizes;
  std::vector<char> entry;
  receiveVector(world, from, sizes);
  receiveVector(world, from, entry);
  f.entry = nlohmann::json::parse(entry.begin(), entry.end());
  f.image.width = sizes[0], f.image.height = sizes[1];
  f.own.width = sizes[2], f.own.height = sizes[3];
  receiveVector(world, from, f.image.depth);
  receiveVector(world, from, f.image.color);
  receiveVector(world, from, f.image.id);
  receiveVector(world, from, f.own.centreId);
  receiveVector(world, from, f.own.subsampleId);
  receiveVector(world, from, f.own.boxColor);
  return f;
}

}  // namespace lzb
