#pragma once
// The MPI link between the node server and its clients (section 6.1's client-server, over MPI
// instead of TCP): a communicator of its own (a duplicate of the world's, so node traffic never
// meets the frames' compositing), the server's rank (the last: rank 0 writes the images, so it
// renders), the message tags, and transfers that wait by polling with short sleeps (Open MPI's
// blocking waits spin a core, which the render ranks' threads need; on one machine they share it).
// The node cache's loader thread sends requests while the frame thread composites, so the link
// needs MPI_THREAD_MULTIPLE (src/cli/main.cpp asks for it when --node-server is given).
#include <mpi.h>

#include <cstddef>
#include <cstdint>
#include <string>

#include "mpi/group.hpp"
#include "src/sampletree/sample_tree.hpp"

namespace lzb::sampletree {

enum NodeTag : int {
  kNodeRequest = 1,  // client -> server: node indices (uint32)
  kNodePayload = 2,  // server -> client: their positions, IDs and colours, node after node
  kFrameDrawn = 3,   // client -> server: this rank has drawn its share of the frame
  kGoodbye = 4,      // client -> server: no more requests from this rank
};

class NodeLink {
 public:
  NodeLink();  // collective over MPI_COMM_WORLD
  ~NodeLink();
  NodeLink(const NodeLink&) = delete;
  NodeLink& operator=(const NodeLink&) = delete;

  const mpi::Group& group() const { return group_; }
  MPI_Comm comm() const { return group_.comm; }
  int server() const { return group_.size - 1; }
  bool serving() const { return group_.rank == server(); }
  int clients() const { return group_.size - 1; }

 private:
  mpi::Group group_;
};

// Ranks of MPI_COMM_WORLD (1 when MPI is not initialised, as in unit tests).
int worldRanks();
// Whether threads other than the main one may call MPI (MPI_THREAD_MULTIPLE was provided).
bool threadsMayCallMpi();

// Sends or receives `bytes` bytes (in chunks of at most 1 GiB: MPI counts are ints), waiting by
// polling.
void sendPolling(const void* data, size_t bytes, int peer, int tag, MPI_Comm comm);
void receivePolling(void* data, size_t bytes, int peer, int tag, MPI_Comm comm);
// Waits, polling, for the next message from any rank on comm.
MPI_Status probePolling(MPI_Comm comm);

// The server's outcome of opening the store, shared: status 0 returns; else every rank throws
// the server's message (InputError for status 2). Collective over the link.
void shareOutcome(const NodeLink& link, int status, const std::string& message);

// What the render ranks need of the store besides the payloads.
struct StoreTable {
  SampleTree tree;  // without triangles
  uint64_t triangles = 0, fileBytes = 0;
};
// The server's node table to every client: the server sends, the clients receive (collective
// over the link).
void sendTable(const NodeLink& link, const SampleTree& tree, uint64_t triangles, uint64_t fileBytes);
StoreTable receiveTable(const NodeLink& link);

}  // namespace lzb::sampletree
