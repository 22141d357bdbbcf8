#include "src/sampletree/node_cache.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

#include "src/core/timer.hpp"

namespace lzb::sampletree {

NodeCache::NodeCache(NodeSource& source, uint64_t budgetBytes)
    : source_(source), budget_(budgetBytes), fileBytesSeen_(source.fileBytesRead()) {
  loader_ = std::thread(&NodeCache::loaderLoop, this);
}

NodeCache::~NodeCache() {
  {
    std::lock_guard lock(mutex_);
    stop_ = true;
  }
  work_.notify_all();
  loader_.join();
}

void NodeCache::beginFrame() {
  std::lock_guard lock(mutex_);
  ++frame_;
  prefetch_.clear();
}

std::vector<const NodePayload*> NodeCache::acquire(std::span<const uint32_t> nodes) {
  std::unique_lock lock(mutex_);
  rethrowLocked();
  uint64_t missing = 0;
  for (uint32_t n : nodes) {
    auto [it, fresh] = entries_.try_emplace(n);
    Entry& e = it->second;
    if (fresh) {
      demand_.push_back(n);
      ++missing;
    } else if (e.state == State::kResident) {
      if (e.pins == 0) unlinkLru(e);
      ++counters_.hits;
    } else {
      ++missing;  // being prefetched now
    }
    ++e.pins;
  }
  if (missing > 0) {
    Stopwatch wait;
    awaited_ = missing;
    work_.notify_one();
    loaded_.wait(lock, [&] { return error_ || awaited_ == 0; });
    counters_.waitSeconds += wait.seconds();
  }
  rethrowLocked();
  std::vector<const NodePayload*> out;
  out.reserve(nodes.size());
  for (uint32_t n : nodes) out.push_back(entries_.at(n).payload.get());
  return out;
}

void NodeCache::release(std::span<const uint32_t> nodes) {
  std::lock_guard lock(mutex_);
  for (uint32_t n : nodes) {
    Entry& e = entries_.at(n);
    if (--e.pins == 0 && e.state == State::kResident) unpinToLru(n, e);
  }
}

std::vector<uint32_t> NodeCache::residentFirst(std::span<const uint32_t> nodes) const {
  std::vector<uint32_t> out(nodes.begin(), nodes.end());
  std::lock_guard lock(mutex_);
  std::stable_partition(out.begin(), out.end(), [&](uint32_t n) {
    const auto it = entries_.find(n);
    return it != entries_.end() && it->second.state == State::kResident;
  });
  return out;
}

void NodeCache::touch(std::span<const uint32_t> nodes) {
  std::lock_guard lock(mutex_);
  for (uint32_t n : nodes) {
    const auto it = entries_.find(n);
    if (it == entries_.end() || it->second.state != State::kResident || it->second.pins > 0) continue;
    unlinkLru(it->second);
    unpinToLru(n, it->second);
  }
}

void NodeCache::prefetch(std::vector<uint32_t> nodes) {
  {
    std::lock_guard lock(mutex_);
    prefetch_.assign(nodes.begin(), nodes.end());
  }
  work_.notify_one();
}

void NodeCache::drain() {
  std::unique_lock lock(mutex_);
  loaded_.wait(lock, [&] { return error_ || (demand_.empty() && prefetch_.empty() && !busy_); });
  rethrowLocked();
}

void NodeCache::check() {
  std::lock_guard lock(mutex_);
  rethrowLocked();
}

CacheCounters NodeCache::takeCounters() {
  std::lock_guard lock(mutex_);
  CacheCounters c = counters_;
  const uint64_t read = source_.fileBytesRead();
  c.fileBytesRead = read - fileBytesSeen_;
  fileBytesSeen_ = read;
  counters_ = {};
  return c;
}

uint64_t NodeCache::residentBytes() const {
  std::lock_guard lock(mutex_);
  return used_;
}

void NodeCache::loaderLoop() {
  std::unique_lock lock(mutex_);
  std::vector<uint32_t> batch;
  for (;;) {
    bool demand = false;
    if (!nextBatch(lock, batch, demand)) return;
    lock.unlock();
    std::vector<NodePayload> payloads;
    std::exception_ptr error;
    try {
      payloads = source_.readNodes(batch);
    } catch (...) {
      error = std::current_exception();
    }
    lock.lock();
    busy_ = false;
    if (error) {  // the store is damaged: every later acquire fails with this error
      error_ = error;
      loaded_.notify_all();
      return;
    }
    for (size_t i = 0; i < batch.size(); ++i)
      finishLoad(batch[i], std::make_unique<NodePayload>(std::move(payloads[i])), demand);
    loaded_.notify_all();
  }
}

// The next nodes to load, their bytes reserved: demand first, then prefetch into room that older
// frames leave. Waits while there is nothing to do; false when stopping or failed.
bool NodeCache::nextBatch(std::unique_lock<std::mutex>& lock, std::vector<uint32_t>& batch,
                          bool& demand) {
  batch.clear();
  for (;;) {
    if (stop_ || error_) return false;
    if (!demand_.empty()) {
      demand = true;
      if (!takeDemand(batch)) return false;
      busy_ = true;
      return true;
    }
    takePrefetch(batch);
    if (!batch.empty()) {
      demand = false;
      busy_ = true;
      return true;
    }
    loaded_.notify_all();  // idle: drain() may return
    work_.wait(lock);
  }
}

// Moves demanded nodes into `batch` (one message to a node server; the frame waits for all of
// them anyway). False (and error_ set) when one finds no room: acquire() keeps a batch within the
// budget, so that is a bug.
bool NodeCache::takeDemand(std::vector<uint32_t>& batch) {
  constexpr size_t kMaxNodes = 4096;
  while (!demand_.empty() && batch.size() < kMaxNodes) {
    const uint32_t node = demand_.front();
    demand_.pop_front();
    const uint64_t bytes = cachedBytes(source_.table().nodes[node]);
    if (!makeRoom(bytes, true)) {
      error_ = std::make_exception_ptr(std::logic_error(
          "node cache: no room for node " + std::to_string(node) + " within the budget"));
      loaded_.notify_all();
      return false;
    }
    used_ += bytes;
    batch.push_back(node);
  }
  return true;
}

// Moves a few prefetch nodes that fit into `batch`: few, so that a demand arriving meanwhile
// waits for at most a short batch.
void NodeCache::takePrefetch(std::vector<uint32_t>& batch) {
  constexpr size_t kMaxNodes = 64;
  constexpr uint64_t kMaxBytes = 256 * 1024;
  uint64_t taken = 0;
  while (!prefetch_.empty() && batch.size() < kMaxNodes && taken < kMaxBytes) {
    const uint32_t node = prefetch_.front();
    prefetch_.pop_front();
    const uint64_t bytes = cachedBytes(source_.table().nodes[node]);
    if (entries_.count(node) || !makeRoom(bytes, false)) continue;
    entries_.try_emplace(node);
    used_ += bytes;
    taken += bytes;
    batch.push_back(node);
  }
}

// Evicts least recently used unpinned nodes until `bytes` more fit; prefetch evicts only nodes
// of earlier frames. False when that cannot make the room.
bool NodeCache::makeRoom(uint64_t bytes, bool demand) {
  if (bytes > budget_) return false;
  while (used_ + bytes > budget_) {
    if (!oldest_) return false;
    if (!demand && oldest_->frame >= frame_) return false;
    const uint32_t victim = oldest_->node;
    used_ -= cachedBytes(source_.table().nodes[victim]);
    unlinkLru(*oldest_);
    entries_.erase(victim);
    ++counters_.evicted;
  }
  return true;
}

void NodeCache::finishLoad(uint32_t node, std::unique_ptr<NodePayload> payload, bool demand) {
  Entry& e = entries_.at(node);
  e.payload = std::move(payload);
  e.state = State::kResident;
  ++counters_.nodesLoaded;
  counters_.nodesPrefetched += demand ? 0 : 1;
  counters_.bytesRead += payloadBytes(source_.table().nodes[node]);
  if (e.pins > 0)
    --awaited_;  // the current acquire() waits for it
  else
    unpinToLru(node, e);
}

void NodeCache::unpinToLru(uint32_t node, Entry& e) {
  e.node = node;
  e.frame = frame_;
  e.older = newest_;
  e.newer = nullptr;
  (newest_ ? newest_->newer : oldest_) = &e;
  newest_ = &e;
}

void NodeCache::unlinkLru(Entry& e) {
  (e.older ? e.older->newer : oldest_) = e.newer;
  (e.newer ? e.newer->older : newest_) = e.older;
  e.older = e.newer = nullptr;
}

void NodeCache::rethrowLocked() {
  if (error_) std::rethrow_exception(error_);
}

}  // namespace lzb::sampletree
