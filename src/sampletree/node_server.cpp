#include "src/sampletree/node_server.hpp"

#include <stdexcept>

#include "mpi/failure.hpp"

namespace lzb::sampletree {

namespace {

// The store opened on this rank, or the reason it could not be (shared with every rank).
std::unique_ptr<StoreReader> openStore(const NodeLink& link, const std::string& path) {
  std::unique_ptr<StoreReader> store;
  int status = 0;
  std::string message;
  try {
    store = std::make_unique<StoreReader>(path);
  } catch (const std::exception& e) {
    status = mpi::statusOf(e);
    message = e.what();
  }
  shareOutcome(link, status, message);
  return store;
}

}  // namespace

NodeServer::NodeServer(const NodeLink& link, const std::string& path)
    : link_(link), store_(openStore(link, path)) {
  sendTable(link, store_->table(), store_->triangles(), store_->fileBytes());
  fileBytesSeen_ = store_->fileBytesRead();
  thread_ = std::thread(&NodeServer::serve, this);
}

NodeServer::~NodeServer() { thread_.join(); }

ServerCounters NodeServer::awaitFrame() {
  std::unique_lock lock(mutex_);
  framesAwaited_ += uint64_t(link_.clients());
  drawn_.wait(lock, [&] { return framesDrawn_ >= framesAwaited_; });
  ServerCounters c = counters_;
  counters_ = {};
  const uint64_t read = store_->fileBytesRead();
  c.fileBytesRead = read - fileBytesSeen_;
  fileBytesSeen_ = read;
  return c;
}

// The serving thread. A store found damaged here ends the job (its message names the store and
// the block): the render ranks wait for this reply, so no rank could go on.
void NodeServer::serve() {
  try {
    for (int goodbyes = 0; goodbyes < link_.clients();) {
      const MPI_Status status = probePolling(link_.comm());
      if (status.MPI_TAG == kNodeRequest) {
        answer(status);
        continue;
      }
      int frame = 0;
      LZB_MPI_CALL(MPI_Recv(&frame, 1, MPI_INT, status.MPI_SOURCE, status.MPI_TAG, link_.comm(),
                            MPI_STATUS_IGNORE));
      if (status.MPI_TAG == kGoodbye) {
        ++goodbyes;
      } else if (status.MPI_TAG == kFrameDrawn) {
        std::lock_guard lock(mutex_);
        ++framesDrawn_;
        drawn_.notify_all();
      } else {
        throw std::logic_error("node server: a message with unknown tag " +
                               std::to_string(status.MPI_TAG));
      }
    }
  } catch (const std::exception& e) {
    mpi::abortJob(link_.group(), e);
  }
}

// Reads the requested nodes and sends them back in one message: each node's positions, then its
// IDs, then its colours, in the order asked.
void NodeServer::answer(const MPI_Status& request) {
  int count = 0;
  LZB_MPI_CALL(MPI_Get_count(&request, MPI_UINT32_T, &count));
  std::vector<uint32_t> nodes(static_cast<size_t>(count));
  LZB_MPI_CALL(MPI_Recv(nodes.data(), count, MPI_UINT32_T, request.MPI_SOURCE, kNodeRequest,
                        link_.comm(), MPI_STATUS_IGNORE));
  for (uint32_t n : nodes)
    if (n >= store_->table().nodes.size())
      throw std::logic_error("node server: asked for node " + std::to_string(n) + " of " +
                             std::to_string(store_->table().nodes.size()));
  const std::vector<NodePayload> payloads = store_->readNodes(nodes);
  reply_.clear();
  for (const NodePayload& p : payloads) {
    const auto* pos = reinterpret_cast<const char*>(p.positions.data());
    const auto* ids = reinterpret_cast<const char*>(p.ids.data());
    const auto* colours = reinterpret_cast<const char*>(p.colours.data());
    reply_.insert(reply_.end(), pos, pos + p.positions.size() * sizeof(glm::vec3));
    reply_.insert(reply_.end(), ids, ids + p.ids.size() * sizeof(uint64_t));
    reply_.insert(reply_.end(), colours, colours + p.colours.size() * sizeof(Rgba8));
  }
  sendPolling(reply_.data(), reply_.size(), request.MPI_SOURCE, kNodePayload, link_.comm());
  std::lock_guard lock(mutex_);
  ++counters_.requests;
  counters_.nodes += nodes.size();
  counters_.bytes += reply_.size();
}

}  // namespace lzb::sampletree
