#pragma once
// The node cache of section 6.2: node payloads (positions, IDs, colours) loaded from a node source (the
// store, or a node server on another rank) on demand by one background loader thread, within a
// byte budget. The loader asks for several nodes at once (one message to a node server). A frame acquires the nodes it draws
// (the loader loads the missing ones first; the frame waits for them) and may queue nodes to
// prefetch (loaded while the frame goes on, only into room that older frames' nodes leave).
// Eviction: the least recently used frame's nodes first; nodes acquired and not yet released are
// never evicted. A load that fails (a corrupted block) is rethrown by the next acquire or check.
#include <absl/container/node_hash_map.h>

#include <condition_variable>
#include <cstdint>
#include <deque>
#include <exception>
#include <memory>
#include <mutex>
#include <span>
#include <thread>
#include <vector>

#include "src/sampletree/node_source.hpp"

namespace lzb::sampletree {

// What the cache did since the last takeCounters().
struct CacheCounters {
  uint64_t nodesLoaded = 0;     // demand and prefetch loads completed
  uint64_t nodesPrefetched = 0;  // of which prefetch
  uint64_t bytesRead = 0;       // the loaded nodes' payload bytes
  uint64_t fileBytesRead = 0;   // bytes read from the store (whole checked blocks) on this rank
  uint64_t hits = 0;            // acquired nodes already resident
  uint64_t evicted = 0;
  double waitSeconds = 0.0;     // the frame waiting in acquire()
};

class NodeCache {
 public:
  NodeCache(NodeSource& source, uint64_t budgetBytes);
  ~NodeCache();
  NodeCache(const NodeCache&) = delete;
  NodeCache& operator=(const NodeCache&) = delete;

  uint64_t budget() const { return budget_; }
  // One frame thread calls beginFrame, acquire, release and prefetch.
  // Starts a frame: drops the previous frame's prefetch queue; nodes used now count as this frame.
  void beginFrame();
  // Loads (waiting) and pins `nodes` (their cachedBytes together at most the budget); the
  // returned payloads stay valid until release(nodes).
  std::vector<const NodePayload*> acquire(std::span<const uint32_t> nodes);
  void release(std::span<const uint32_t> nodes);
  // `nodes` with the resident ones first (each part in its order): a frame larger than the cache
  // draws what the last frame left before streaming the rest, instead of evicting it unused.
  std::vector<uint32_t> residentFirst(std::span<const uint32_t> nodes) const;
  // Marks the resident ones of `nodes` used in this frame, so this frame's prefetch spares them.
  void touch(std::span<const uint32_t> nodes);
  // Queues nodes for the loader after any demand (replacing the queue).
  void prefetch(std::vector<uint32_t> nodes);
  // Waits until the loader is idle; rethrows a failed load.
  void drain();
  // Rethrows a failed load, if any.
  void check();
  CacheCounters takeCounters();
  uint64_t residentBytes() const;

 private:
  enum class State { kQueued, kResident };
  struct Entry {
    State state = State::kQueued;
    std::unique_ptr<NodePayload> payload;
    uint32_t pins = 0;
    uint32_t node = 0;
    uint64_t frame = 0;                        // last use
    Entry *older = nullptr, *newer = nullptr;  // the LRU list's neighbours while in it
  };

  void loaderLoop();
  bool nextBatch(std::unique_lock<std::mutex>& lock, std::vector<uint32_t>& batch, bool& demand);
  bool takeDemand(std::vector<uint32_t>& batch);
  void takePrefetch(std::vector<uint32_t>& batch);
  bool makeRoom(uint64_t bytes, bool demand);
  void finishLoad(uint32_t node, std::unique_ptr<NodePayload> payload, bool demand);
  void unpinToLru(uint32_t node, Entry& e);
  void unlinkLru(Entry& e);
  void rethrowLocked();

  NodeSource& source_;
  const uint64_t budget_;
  mutable std::mutex mutex_;
  std::condition_variable work_, loaded_;
  absl::node_hash_map<uint32_t, Entry> entries_;  // node-based: the LRU list links entries
  // Resident, unpinned entries, least recently used first: a node joins at the newest end on
  // each use, so the list is in use order without a search (10^5 nodes a frame at 10^7).
  Entry *oldest_ = nullptr, *newest_ = nullptr;
  std::deque<uint32_t> demand_, prefetch_;
  uint64_t used_ = 0, frame_ = 0;
  uint64_t awaited_ = 0;        // nodes the current acquire() still waits for
  uint64_t fileBytesSeen_ = 0;  // source_.fileBytesRead() at the last takeCounters()
  bool busy_ = false, stop_ = false;
  std::exception_ptr error_;
  CacheCounters counters_;
  std::thread loader_;  // last: started when everything above exists
};

}  // namespace lzb::sampletree
