#pragma once
// Depth compositing across ranks: the per-pixel minimum over (depth, id) of every rank's
// framebuffer, gathered at the root. The operation is commutative and associative, so the result
// does not depend on the number of ranks or the reduction order.
#include <string>
#include <vector>

#include "mpi/group.hpp"
#include "src/core/framebuffer.hpp"

namespace lzb::mpi {

struct CompositeStats {
  double seconds = 0.0;
  double bytesSent = 0.0;  // by this rank
};

// After the call, the root's fb holds the composite; other ranks' fb is unspecified.
CompositeStats compositeAtRoot(const Group& g, Framebuffer& fb);

// Gathers one string per rank at the root (empty vector elsewhere).
std::vector<std::string> gatherStrings(const Group& g, const std::string& mine);
// Broadcasts a flag from the root so every rank takes the same branch after a root-only check.
bool broadcastFlag(const Group& g, bool value);
std::string broadcastString(const Group& g, const std::string& value);

}  // namespace lzb::mpi
