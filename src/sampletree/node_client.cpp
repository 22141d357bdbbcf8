#include "src/sampletree/node_client.hpp"

#include <cstring>

#include "src/core/timer.hpp"

namespace lzb::sampletree {

namespace {

const NodeLink& opened(const NodeLink& link) {
  shareOutcome(link, 0, "");
  return link;
}

}  // namespace

NodeClient::Goodbye::~Goodbye() {
  if (!link) return;
  int none = 0;
  // A goodbye that cannot be sent leaves the server waiting; the job is failing then anyway.
  MPI_Send(&none, 1, MPI_INT, link->server(), kGoodbye, link->comm());
}

NodeClient::NodeClient(const NodeLink& link) : link_(opened(link)) {
  goodbye_.link = &link;
  table_ = receiveTable(link);
}

std::vector<NodePayload> NodeClient::readNodes(std::span<const uint32_t> nodes) {
  uint64_t bytes = 0;
  for (uint32_t n : nodes) bytes += payloadBytes(table_.tree.nodes.at(n));
  reply_.resize(size_t(bytes));
  Stopwatch wait;
  sendPolling(nodes.data(), nodes.size() * sizeof(uint32_t), link_.server(), kNodeRequest,
              link_.comm());
  receivePolling(reply_.data(), reply_.size(), link_.server(), kNodePayload, link_.comm());
  waitNanoseconds_ += uint64_t(wait.seconds() * 1e9);
  std::vector<NodePayload> out(nodes.size());
  const char* at = reply_.data();
  for (size_t k = 0; k < nodes.size(); ++k) {
    const size_t count = table_.tree.nodes[nodes[k]].triangleCount;
    out[k].positions.resize(3 * count);
    out[k].ids.resize(count);
    out[k].colours.resize(count);
    std::memcpy(out[k].positions.data(), at, 3 * count * sizeof(glm::vec3));
    at += 3 * count * sizeof(glm::vec3);
    std::memcpy(out[k].ids.data(), at, count * sizeof(uint64_t));
    at += count * sizeof(uint64_t);
    std::memcpy(out[k].colours.data(), at, count * sizeof(Rgba8));
    at += count * sizeof(Rgba8);
  }
  return out;
}

void NodeClient::frameDrawn(int frame) {
  LZB_MPI_CALL(MPI_Send(&frame, 1, MPI_INT, link_.server(), kFrameDrawn, link_.comm()));
}

double NodeClient::takeWaitSeconds() { return double(waitNanoseconds_.exchange(0)) * 1e-9; }

}  // namespace lzb::sampletree
