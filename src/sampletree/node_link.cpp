#include "src/sampletree/node_link.hpp"

#include <algorithm>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

#include "src/core/error.hpp"

namespace lzb::sampletree {

namespace {

constexpr size_t kChunkBytes = size_t(1) << 30;

// Polls until every request is done: a few yields first (a reply usually comes fast), then sleeps
// growing to 200 us, so an idle wait costs no core.
void waitAll(std::vector<MPI_Request>& requests) {
  auto pause = std::chrono::microseconds(5);
  for (int tries = 0;; ++tries) {
    int done = 0;
    LZB_MPI_CALL(MPI_Testall(int(requests.size()), requests.data(), &done, MPI_STATUSES_IGNORE));
    if (done) return;
    if (tries < 64) {
      std::this_thread::yield();
      continue;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(200));
  }
}

// The message layout of the table's head.
struct TableHead {
  double c = 0.0;
  uint64_t seed = 0;
  uint32_t leafTriangles = 0, pad = 0;
  double origin[3] = {0.0, 0.0, 0.0};
  double size = 0.0;
  uint64_t sceneTriangles = 0, nodes = 0, triangles = 0, fileBytes = 0;
};

}  // namespace

NodeLink::NodeLink() {
  LZB_MPI_CALL(MPI_Comm_dup(MPI_COMM_WORLD, &group_.comm));
  MPI_Comm_set_errhandler(group_.comm, MPI_ERRORS_RETURN);  // errors as exceptions
  LZB_MPI_CALL(MPI_Comm_rank(group_.comm, &group_.rank));
  LZB_MPI_CALL(MPI_Comm_size(group_.comm, &group_.size));
}

NodeLink::~NodeLink() { MPI_Comm_free(&group_.comm); }

int worldRanks() {
  int initialised = 0, size = 1;
  MPI_Initialized(&initialised);
  if (initialised) MPI_Comm_size(MPI_COMM_WORLD, &size);
  return size;
}

bool threadsMayCallMpi() {
  int initialised = 0, provided = MPI_THREAD_SINGLE;
  MPI_Initialized(&initialised);
  if (initialised) MPI_Query_thread(&provided);
  return provided == MPI_THREAD_MULTIPLE;
}

void sendPolling(const void* data, size_t bytes, int peer, int tag, MPI_Comm comm) {
  std::vector<MPI_Request> requests(std::max<size_t>(1, (bytes + kChunkBytes - 1) / kChunkBytes));
  const auto* p = static_cast<const char*>(data);
  for (size_t k = 0; k < requests.size(); ++k) {
    const size_t at = k * kChunkBytes;
    LZB_MPI_CALL(MPI_Isend(p + at, int(std::min(kChunkBytes, bytes - at)), MPI_BYTE, peer, tag,
                           comm, &requests[k]));
  }
  waitAll(requests);
}

void receivePolling(void* data, size_t bytes, int peer, int tag, MPI_Comm comm) {
  std::vector<MPI_Request> requests(std::max<size_t>(1, (bytes + kChunkBytes - 1) / kChunkBytes));
  auto* p = static_cast<char*>(data);
  for (size_t k = 0; k < requests.size(); ++k) {
    const size_t at = k * kChunkBytes;
    LZB_MPI_CALL(MPI_Irecv(p + at, int(std::min(kChunkBytes, bytes - at)), MPI_BYTE, peer, tag,
                           comm, &requests[k]));
  }
  waitAll(requests);
}

MPI_Status probePolling(MPI_Comm comm) {
  auto pause = std::chrono::microseconds(5);
  for (int tries = 0;; ++tries) {
    int found = 0;
    MPI_Status status;
    LZB_MPI_CALL(MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, comm, &found, &status));
    if (found) return status;
    if (tries < 64) {
      std::this_thread::yield();
      continue;
    }
    std::this_thread::sleep_for(pause);
    pause = std::min(pause * 2, std::chrono::microseconds(200));
  }
}

void shareOutcome(const NodeLink& link, int status, const std::string& message) {
  LZB_MPI_CALL(MPI_Bcast(&status, 1, MPI_INT, link.server(), link.comm()));
  if (status == 0) return;
  uint64_t length = message.size();
  LZB_MPI_CALL(MPI_Bcast(&length, 1, MPI_UINT64_T, link.server(), link.comm()));
  std::string text = message;
  text.resize(size_t(length));
  LZB_MPI_CALL(MPI_Bcast(text.data(), int(length), MPI_CHAR, link.server(), link.comm()));
  if (status == 2) throw InputError(text);
  throw std::runtime_error(text);
}

namespace {

void broadcastNodes(const NodeLink& link, std::vector<TreeNode>& nodes) {
  auto* bytes = reinterpret_cast<char*>(nodes.data());
  const size_t total = nodes.size() * sizeof(TreeNode);
  for (size_t at = 0; at < total; at += kChunkBytes)
    LZB_MPI_CALL(MPI_Bcast(bytes + at, int(std::min(kChunkBytes, total - at)), MPI_BYTE,
                           link.server(), link.comm()));
}

}  // namespace

void sendTable(const NodeLink& link, const SampleTree& t, uint64_t triangles, uint64_t fileBytes) {
  TableHead head{t.params.c, t.params.seed, t.params.leafTriangles, 0,
                 {t.origin.x, t.origin.y, t.origin.z}, t.size, t.sceneTriangles,
                 t.nodes.size(), triangles, fileBytes};
  LZB_MPI_CALL(MPI_Bcast(&head, int(sizeof(head)), MPI_BYTE, link.server(), link.comm()));
  // MPI_Bcast takes a non-const buffer even at its root, which only reads it.
  broadcastNodes(link, const_cast<std::vector<TreeNode>&>(t.nodes));
}

StoreTable receiveTable(const NodeLink& link) {
  TableHead head;
  LZB_MPI_CALL(MPI_Bcast(&head, int(sizeof(head)), MPI_BYTE, link.server(), link.comm()));
  StoreTable table;
  SampleTree& t = table.tree;
  t.params = {head.c, head.seed, head.leafTriangles};
  t.origin = {head.origin[0], head.origin[1], head.origin[2]};
  t.size = head.size;
  t.sceneTriangles = head.sceneTriangles;
  t.nodes.resize(size_t(head.nodes));
  table.triangles = head.triangles;
  table.fileBytes = head.fileBytes;
  broadcastNodes(link, t.nodes);
  return table;
}

}  // namespace lzb::sampletree
