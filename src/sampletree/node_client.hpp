#pragma once
// A render rank's side of the node server (node_server.hpp): the node table received from the
// server at start (the paper's client gets everything from the server, so render ranks need no
// access to the store's file), and node payloads fetched on request, one message per batch the
// node cache's loader asks for.
#include <atomic>
#include <cstdint>
#include <span>
#include <vector>

#include "src/sampletree/node_link.hpp"
#include "src/sampletree/node_source.hpp"

namespace lzb::sampletree {

class NodeClient : public NodeSource {
 public:
  // Receives the server's outcome of opening the store (throwing its error) and the node table:
  // collective with the NodeServer constructor.
  explicit NodeClient(const NodeLink& link);
  NodeClient(const NodeClient&) = delete;
  NodeClient& operator=(const NodeClient&) = delete;

  const SampleTree& table() const override { return table_.tree; }
  uint64_t triangles() const { return table_.triangles; }
  uint64_t fileBytes() const { return table_.fileBytes; }
  // One request to the server, one reply (the loader thread).
  std::vector<NodePayload> readNodes(std::span<const uint32_t> nodes) override;
  uint64_t fileBytesRead() const override { return 0; }  // the server reads the store
  // Tells the server this rank has drawn its share of the frame (the frame thread).
  void frameDrawn(int frame);
  // Seconds the loader waited for replies since the last call.
  double takeWaitSeconds();

 private:
  // Says goodbye when the client goes, also when its constructor fails after the store opened
  // (the server serves until every client has said it): declared first, destroyed last.
  struct Goodbye {
    const NodeLink* link = nullptr;
    ~Goodbye();
  };

  Goodbye goodbye_;
  const NodeLink& link_;
  StoreTable table_;
  std::vector<char> reply_;  // the loader's message buffer
  std::atomic<uint64_t> waitNanoseconds_{0};
};

}  // namespace lzb::sampletree
