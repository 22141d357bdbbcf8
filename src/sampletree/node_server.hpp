#pragma once
// The node server (section 6.1, the paper's node manager): one rank opens the store and answers
// the render ranks' node requests from a thread of its own, for the whole run (their loaders ask
// for nodes while frames composite, and prefetch between frames). It draws nothing. Per frame it
// waits until every render rank has drawn its share, and reports what it served.
#include <condition_variable>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "src/sampletree/node_link.hpp"
#include "src/sampletree/store_reader.hpp"

namespace lzb::sampletree {

// What the server did since the last awaitFrame().
struct ServerCounters {
  uint64_t requests = 0;       // request messages answered
  uint64_t nodes = 0;          // nodes sent
  uint64_t bytes = 0;          // payload bytes sent (44 a triangle)
  uint64_t fileBytesRead = 0;  // bytes read from the store (whole checked blocks)
};

class NodeServer {
 public:
  // Opens the store, shares its outcome and node table with the clients (collective with their
  // NodeClient constructors: a store that fails fails on every rank alike) and starts serving.
  NodeServer(const NodeLink& link, const std::string& path);
  // Serves until every client has said goodbye (they do when their renderer ends).
  ~NodeServer();
  NodeServer(const NodeServer&) = delete;
  NodeServer& operator=(const NodeServer&) = delete;

  const StoreReader& store() const { return *store_; }
  // Waits until every client has drawn the current frame; what was served since the last call.
  ServerCounters awaitFrame();

 private:
  void serve();
  void answer(const MPI_Status& request);

  const NodeLink& link_;
  std::unique_ptr<StoreReader> store_;
  std::vector<char> reply_;  // the serving thread's message buffer
  std::mutex mutex_;
  std::condition_variable drawn_;
  uint64_t framesDrawn_ = 0, framesAwaited_ = 0;  // kFrameDrawn messages received, consumed
  uint64_t fileBytesSeen_ = 0;
  ServerCounters counters_;
  std::thread thread_;  // last: started when everything above exists
};

}  // namespace lzb::sampletree
